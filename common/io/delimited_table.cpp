#include "common/io/delimited_table.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <map>

#include "common/io/input_error.hpp"
#include "common/io/text_file_lines.hpp"

namespace ldv {
namespace {

// Enough lines for a preamble and a header, and for the rows to outnumber them.
constexpr int kSniffLines = 200;

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t' || s.front() == '\r')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

bool is_comment(std::string_view line) {
  line = trim(line);
  return line.empty() || line.front() == '#';
}

void split(std::string_view line, char separator, std::vector<std::string_view>& fields) {
  fields.clear();
  line = trim(line);
  if (line.empty()) return;
  if (separator == ' ') {
    size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
      if (i >= line.size()) break;
      size_t j = i;
      if (line[i] == '"') {
        j = line.find('"', i + 1);
        j = j == std::string_view::npos ? line.size() : j + 1;
      }
      while (j < line.size() && line[j] != ' ' && line[j] != '\t') ++j;
      std::string_view f = line.substr(i, j - i);
      if (f.size() >= 2 && f.front() == '"' && f.back() == '"') f = f.substr(1, f.size() - 2);
      fields.push_back(f);
      i = j;
    }
    return;
  }
  size_t i = 0;
  for (;;) {
    size_t j = i;
    // A quoted field runs to its closing quote (a separator inside it is text).
    size_t lead = i;
    while (lead < line.size() && line[lead] == ' ') ++lead;
    if (lead < line.size() && line[lead] == '"') {
      const size_t close = line.find('"', lead + 1);
      j = close == std::string_view::npos ? line.size() : close + 1;
    }
    j = line.find(separator, j);
    if (j == std::string_view::npos) j = line.size();
    std::string_view f = trim(line.substr(i, j - i));
    if (f.size() >= 2 && f.front() == '"' && f.back() == '"') f = f.substr(1, f.size() - 2);
    fields.push_back(f);
    if (j >= line.size()) break;
    i = j + 1;
  }
}

bool parse_number(std::string_view field, bool decimal_comma, double& value) {
  field = trim(field);
  if (field.empty()) return false;
  char buf[64];
  if (decimal_comma && field.find(',') != std::string_view::npos) {
    if (field.size() >= sizeof buf) return false;
    std::copy(field.begin(), field.end(), buf);
    std::replace(buf, buf + field.size(), ',', '.');
    field = std::string_view(buf, field.size());
  }
  const char* begin = field.data();
  const char* end = begin + field.size();
  if (*begin == '+') ++begin;
  const auto [ptr, ec] = std::from_chars(begin, end, value);
  return ec == std::errc() && ptr == end && std::isfinite(value);
}

// Which fields of a line are numbers.
std::vector<bool> numeric_pattern(const std::vector<std::string_view>& fields, bool decimal_comma) {
  std::vector<bool> p(fields.size());
  double v = 0.0;
  for (size_t k = 0; k < fields.size(); ++k) p[k] = parse_number(fields[k], decimal_comma, v);
  return p;
}

bool looks_like_decimal_comma(std::string_view f) {
  f = trim(f);
  const size_t comma = f.find(',');
  if (comma == std::string_view::npos || comma == 0 || comma + 1 >= f.size()) return false;
  if (f.find('.') != std::string_view::npos) return false;
  const auto digits = [](std::string_view s) {
    if (!s.empty() && (s.front() == '-' || s.front() == '+')) s.remove_prefix(1);
    return !s.empty() &&
           std::all_of(s.begin(), s.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); });
  };
  const std::string_view mantissa_end = f.substr(comma + 1);
  const size_t e = mantissa_end.find_first_of("eE");
  return digits(f.substr(0, comma)) && digits(mantissa_end.substr(0, e));
}

struct SampleLine {
  long line_no;
  std::string text;
};

}  // namespace

std::string TableLayout::describe() const {
  const char* sep = separator == ',' ? "comma" : separator == ';' ? "semicolon" : separator == '\t' ? "tab" : "space";
  std::string s = std::string(sep) + "-separated" + (decimal_comma ? " with decimal commas" : "") + ", " +
                  std::to_string(columns) + " columns, ";
  if (header.empty()) {
    s += "no header (columns by 1-based index)";
  } else {
    s += "header on line " + std::to_string(header_line) + " (";
    for (size_t k = 0; k < header.size(); ++k) s += (k ? ", " : "") + header[k];
    s += ")";
  }
  return s + ", rows from line " + std::to_string(first_row_line);
}

TableLayout sniff_table_layout(const std::string& path) {
  TextFileLines lines(path);
  std::vector<SampleLine> sample;
  std::string_view line;
  TableLayout layout;
  bool separator_given = false;
  while (static_cast<int>(sample.size()) < kSniffLines && lines.next(line)) {
    const std::string_view t = trim(line);
    if (lines.line_number() == 1 && t.size() == 5 && t.substr(0, 4) == "sep=") {
      layout.separator = t[4] == ' ' ? ' ' : t[4];
      separator_given = true;
      continue;
    }
    if (t.empty()) continue;
    sample.push_back({lines.line_number(), std::string(t)});
  }
  if (sample.empty())
    throw InputError(path, 0, "empty file: expected rows of numbers (a header line naming the columns may come first)");

  std::vector<std::string_view> fields;
  const size_t tail_begin = sample.size() / 2;  // the rows outnumber the preamble there
  // The field count most of the sample's later half has, and how many numbers those lines hold.
  const auto modal_count = [&](char sep, bool decimal_comma, long* numbers) {
    std::map<size_t, long> lines_with;
    for (size_t i = tail_begin; i < sample.size(); ++i) {
      if (is_comment(sample[i].text)) continue;
      split(sample[i].text, sep, fields);
      ++lines_with[fields.size()];
    }
    size_t best = 0;
    long most = 0;
    for (const auto& [count, n] : lines_with)
      if (n >= most) best = count, most = n;  // a tie: the more fields (a ragged last line)
    *numbers = 0;
    for (size_t i = tail_begin; i < sample.size(); ++i) {
      if (is_comment(sample[i].text)) continue;
      split(sample[i].text, sep, fields);
      if (fields.size() != best) continue;
      const std::vector<bool> p = numeric_pattern(fields, decimal_comma);
      *numbers += std::count(p.begin(), p.end(), true);
    }
    return best;
  };
  if (!separator_given) {
    long best_numbers = -1;
    for (const char sep : {',', ';', '\t', ' '}) {
      long numbers = 0;
      const bool comma_decimals = sep != ',';
      const size_t count = modal_count(sep, comma_decimals, &numbers);
      if (count > 1 && numbers > best_numbers) best_numbers = numbers, layout.separator = sep;
    }
  }
  // Decimal commas: fields like 0,25 in the rows and none with a point.
  if (layout.separator != ',') {
    bool comma = false, point = false;
    for (size_t i = tail_begin; i < sample.size(); ++i) {
      if (is_comment(sample[i].text)) continue;
      split(sample[i].text, layout.separator, fields);
      for (const std::string_view f : fields) {
        comma = comma || looks_like_decimal_comma(f);
        point = point || f.find('.') != std::string_view::npos;
      }
    }
    layout.decimal_comma = comma && !point;
  }
  long numbers = 0;
  const size_t n = modal_count(layout.separator, layout.decimal_comma, &numbers);
  layout.columns = static_cast<int>(n);
  if (n == 0 || numbers == 0)
    throw InputError(path, sample.front().line_no,
                     "no rows of numbers found in the first " + std::to_string(sample.size()) + " lines");

  // The rows: the first line of that count whose numbers sit where the next line of that count has them (a ragged
  // line between is the reader's to report).
  std::vector<std::vector<bool>> patterns(sample.size());
  std::vector<bool> counted(sample.size(), false);
  for (size_t i = 0; i < sample.size(); ++i) {
    split(sample[i].text, layout.separator, fields);
    counted[i] = fields.size() == n && !is_comment(sample[i].text);
    if (counted[i]) patterns[i] = numeric_pattern(fields, layout.decimal_comma);
  }
  size_t first = sample.size();
  for (size_t i = 0; i < sample.size() && first == sample.size(); ++i) {
    if (!counted[i] || std::find(patterns[i].begin(), patterns[i].end(), true) == patterns[i].end()) continue;
    size_t next = i + 1;
    while (next < sample.size() && !counted[next]) ++next;
    if (next >= sample.size() || patterns[next] == patterns[i]) first = i;
  }
  if (first == sample.size())
    throw InputError(path, sample.front().line_no,
                     "no rows of numbers found in the first " + std::to_string(sample.size()) + " lines");
  layout.first_row_line = sample[first].line_no;
  // The header: the line before, with the rows' count and text where they have numbers (a leading '#' or '%' of a
  // commented header dropped).
  if (first > 0) {
    std::string_view h = sample[first - 1].text;
    while (!h.empty() && (h.front() == '#' || h.front() == '%')) h.remove_prefix(1);
    split(h, layout.separator, fields);
    if (fields.size() == n) {
      const std::vector<bool> hp = numeric_pattern(fields, layout.decimal_comma);
      bool names = false;
      for (size_t k = 0; k < n; ++k) names = names || (patterns[first][k] && !hp[k]);
      if (names) {
        layout.header_line = sample[first - 1].line_no;
        for (const std::string_view f : fields) layout.header.emplace_back(f);
      }
    }
  }
  return layout;
}

int table_column(const TableLayout& layout, const std::string& name_or_index, const std::string& path,
                 const std::string& key) {
  const auto& h = layout.header;
  for (size_t k = 0; k < h.size(); ++k)
    if (h[k] == name_or_index) return static_cast<int>(k);
  const auto lower = [](std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
  };
  int found = -1, matches = 0;
  for (size_t k = 0; k < h.size(); ++k)
    if (lower(h[k]) == lower(name_or_index)) found = static_cast<int>(k), ++matches;
  if (matches == 1) return found;
  int index = 0;
  const char* b = name_or_index.data();
  const auto [ptr, ec] = std::from_chars(b, b + name_or_index.size(), index);
  if (ec == std::errc() && ptr == b + name_or_index.size()) {
    if (index >= 1 && index <= layout.columns) return index - 1;
    throw InputError(path, 0,
                     key + ": column " + name_or_index + " is not in the file (it has " +
                         std::to_string(layout.columns) + " columns, counted from 1)");
  }
  std::string known;
  for (const std::string& name : h) known += (known.empty() ? "" : ", ") + name;
  throw InputError(path, layout.header_line,
                   key + ": no column '" + name_or_index + "'" +
                       (h.empty()     ? " (the file has no header: name columns by their 1-based index)"
                        : matches > 1 ? " (several differ only in case: write it exactly)"
                                      : " (the header names: " + known + ")"));
}

void split_table_line(std::string_view line, const TableLayout& layout, std::vector<std::string_view>& fields) {
  split(line, layout.separator, fields);
}

void for_each_table_row(const std::string& path, const TableLayout& layout,
                        const std::function<void(long, const std::vector<std::string_view>&)>& on_row) {
  TextFileLines lines(path);
  std::string_view line;
  std::vector<std::string_view> fields;
  while (lines.next(line)) {
    if (lines.line_number() < layout.first_row_line || is_comment(line)) continue;
    split(line, layout.separator, fields);
    on_row(lines.line_number(), fields);
  }
}

bool parse_table_number(std::string_view field, const TableLayout& layout, double& value) {
  return parse_number(field, layout.decimal_comma, value);
}

}  // namespace ldv
