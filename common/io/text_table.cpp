#include "common/io/text_table.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>

namespace ldv {

void split_fields(std::string_view line, std::vector<std::string_view>& fields) {
  fields.clear();
  size_t i = 0;
  const size_t n = line.size();
  while (i < n) {
    while (i < n && (line[i] == ' ' || line[i] == '\t' || line[i] == ',' || line[i] == '\r')) ++i;
    if (i >= n) break;
    size_t j = i;
    while (j < n && line[j] != ' ' && line[j] != '\t' && line[j] != ',' && line[j] != '\r') ++j;
    fields.push_back(line.substr(i, j - i));
    i = j;
  }
}

double parse_double(std::string_view field, const std::string& file, long line, int column) {
  double v = 0.0;
  const char* begin = field.data();
  const char* end = begin + field.size();
  if (!field.empty() && *begin == '+') ++begin;
  auto [ptr, ec] = std::from_chars(begin, end, v);
  if (ec != std::errc() || ptr != end) {
    throw InputError(file, line,
                     "column " + std::to_string(column) + ": expected a number, found '" + std::string(field) + "'");
  }
  if (!std::isfinite(v)) {
    throw InputError(file, line,
                     "column " + std::to_string(column) + ": expected a finite number, found '" +
                         std::string(field) + "'");
  }
  return v;
}

void read_numeric_table(const std::string& path, int min_columns, int max_columns,
                        const std::function<void(long, const std::vector<double>&)>& on_row) {
  std::unique_ptr<FILE, int (*)(FILE*)> f(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!f) throw InputError(path, 0, "cannot open file for reading");
  std::vector<char> buffer(1 << 20);
  std::string carry;
  std::vector<std::string_view> fields;
  std::vector<double> values;
  long line_no = 0;
  auto handle_line = [&](std::string_view line) {
    ++line_no;
    split_fields(line, fields);
    if (fields.empty() || fields[0][0] == '#' || fields[0][0] == '%') return;
    const int n = static_cast<int>(fields.size());
    if (n < min_columns || n > max_columns) {
      const std::string expect = min_columns == max_columns
                                     ? std::to_string(min_columns)
                                     : std::to_string(min_columns) + " to " + std::to_string(max_columns);
      throw InputError(path, line_no, "expected " + expect + " columns, found " + std::to_string(n));
    }
    values.resize(n);
    for (int c = 0; c < n; ++c) values[c] = parse_double(fields[c], path, line_no, c + 1);
    on_row(line_no, values);
  };
  size_t got;
  while ((got = std::fread(buffer.data(), 1, buffer.size(), f.get())) > 0) {
    std::string_view chunk(buffer.data(), got);
    size_t start = 0;
    for (size_t i = 0; i < chunk.size(); ++i) {
      if (chunk[i] != '\n') continue;
      if (!carry.empty()) {
        carry.append(chunk.substr(start, i - start));
        handle_line(carry);
        carry.clear();
      } else {
        handle_line(chunk.substr(start, i - start));
      }
      start = i + 1;
    }
    carry.append(chunk.substr(start));
  }
  if (!carry.empty()) handle_line(carry);
}

int format_fixed(char* buf, double value, int decimals) {
  auto res = std::to_chars(buf, buf + 64, value, std::chars_format::fixed, decimals);
  return static_cast<int>(res.ptr - buf);
}

}  // namespace ldv
