#include "common/io/text_table.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>

namespace ldv {
namespace {
inline bool is_separator(char c) { return c == ' ' || c == '\t' || c == ',' || c == '\r'; }
}  // namespace

void split_fields(std::string_view line, std::vector<std::string_view>& fields) {
  fields.clear();
  size_t i = 0;
  const size_t n = line.size();
  while (i < n) {
    while (i < n && is_separator(line[i])) ++i;
    if (i >= n) break;
    size_t j = i;
    while (j < n && !is_separator(line[j])) ++j;
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

TextFileLines::TextFileLines(const std::string& path) : path_(path) {
  file_ = std::fopen(path.c_str(), "rb");
  if (!file_) throw InputError(path, 0, "cannot open file for reading");
  if (std::fseek(file_, 0, SEEK_END) == 0) file_size_ = std::ftell(file_);
  if (std::fseek(file_, 0, SEEK_SET) != 0) file_size_ = -1;
  cap_ = static_cast<size_t>(1) << 20;
  buf_.reset(new char[cap_]);
}

TextFileLines::~TextFileLines() {
  if (file_) std::fclose(file_);
}

bool TextFileLines::refill() {
  if (eof_) return false;
  // Keep the unfinished line at the front; grow only for a line longer than the buffer.
  const size_t rest = end_ - begin_;
  if (rest == cap_) {
    std::unique_ptr<char[]> bigger(new char[2 * cap_]);
    std::memcpy(bigger.get(), buf_.get() + begin_, rest);
    buf_ = std::move(bigger);
    cap_ *= 2;
  } else if (begin_ > 0) {
    std::memmove(buf_.get(), buf_.get() + begin_, rest);
  }
  begin_ = 0;
  end_ = rest;
  const size_t got = std::fread(buf_.get() + end_, 1, cap_ - end_, file_);
  if (got == 0) {
    if (std::ferror(file_)) throw InputError(path_, line_no_ + 1, "read error");
    eof_ = true;
    return false;
  }
  end_ += got;
  return true;
}

bool TextFileLines::next(std::string_view& line) {
  for (;;) {
    const char* b = buf_.get() + begin_;
    const void* nl = std::memchr(b, '\n', end_ - begin_);
    if (nl) {
      const size_t len = static_cast<size_t>(static_cast<const char*>(nl) - b);
      line = std::string_view(b, len);
      begin_ += len + 1;
      ++line_no_;
      return true;
    }
    if (!refill()) break;
  }
  if (begin_ < end_) {  // an unterminated last line
    line = std::string_view(buf_.get() + begin_, end_ - begin_);
    begin_ = end_;
    ++line_no_;
    return true;
  }
  return false;
}

size_t TextFileLines::estimated_lines() {
  if (end_ == begin_) refill();
  const size_t n = end_ - begin_;
  if (n == 0 || file_size_ <= 0) return 0;
  const long lines = static_cast<long>(std::count(buf_.get() + begin_, buf_.get() + end_, '\n'));
  if (lines == 0) return 1;
  return static_cast<size_t>(static_cast<double>(file_size_) * lines / n * 1.02) + 16;
}

int parse_numeric_line(std::string_view line, double* values, int max_store, const std::string& path, long line_no) {
  const char* p = line.data();
  const char* const end = p + line.size();
  int n = 0;
  for (;;) {
    while (p < end && is_separator(*p)) ++p;
    if (p >= end) break;
    if (n == 0 && (*p == '#' || *p == '%')) return 0;
    const char* field = p;
    const char* q = (*p == '+') ? p + 1 : p;
    double v = 0.0;
    auto [ptr, ec] = std::from_chars(q, end, v);
    if (ec != std::errc() || (ptr < end && !is_separator(*ptr)) || !std::isfinite(v)) {
      // Slow path only for the message (same wording as parse_double).
      const char* fe = field;
      while (fe < end && !is_separator(*fe)) ++fe;
      parse_double(std::string_view(field, static_cast<size_t>(fe - field)), path, line_no, n + 1);
      throw InputError(path, line_no, "column " + std::to_string(n + 1) + ": expected a number");
    }
    if (n < max_store) values[n] = v;
    ++n;
    p = ptr;
  }
  return n;
}

void throw_column_count(const std::string& path, long line_no, int min_columns, int max_columns, int found) {
  const std::string expect = min_columns == max_columns
                                 ? std::to_string(min_columns)
                                 : std::to_string(min_columns) + " to " + std::to_string(max_columns);
  throw InputError(path, line_no, "expected " + expect + " columns, found " + std::to_string(found));
}

void read_numeric_table(const std::string& path, int min_columns, int max_columns,
                        const std::function<void(long, const std::vector<double>&)>& on_row) {
  TextFileLines lines(path);
  std::vector<double> values(static_cast<size_t>(std::max(max_columns, 1)));
  std::vector<double> row;
  std::string_view line;
  while (lines.next(line)) {
    const int n = parse_numeric_line(line, values.data(), max_columns, path, lines.line_number());
    if (n == 0) continue;
    if (n < min_columns || n > max_columns) throw_column_count(path, lines.line_number(), min_columns, max_columns, n);
    row.assign(values.begin(), values.begin() + n);
    on_row(lines.line_number(), row);
  }
}

int format_fixed(char* buf, double value, int decimals) {
  static constexpr double kPow10[] = {1e0, 1e1, 1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,
                                      1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16, 1e17};
  static constexpr std::uint64_t kIPow10[] = {1ull,
                                              10ull,
                                              100ull,
                                              1000ull,
                                              10000ull,
                                              100000ull,
                                              1000000ull,
                                              10000000ull,
                                              100000000ull,
                                              1000000000ull,
                                              10000000000ull,
                                              100000000000ull,
                                              1000000000000ull,
                                              10000000000000ull,
                                              100000000000000ull,
                                              1000000000000000ull,
                                              10000000000000000ull,
                                              100000000000000000ull};
  static constexpr char kPairs[] =
      "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
      "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
      "8081828384858687888990919293949596979899";
  if (decimals >= 0 && decimals <= 17) {
    // |value| * 10^d exactly as hi + lo (FMA), rounded to nearest, ties to even: the same digits as
    // std::to_chars / printf.
    const double a = std::fabs(value), p10 = kPow10[decimals];
    const double hi = a * p10;
    if (hi < 4.0e15) {  // < 2^52 (also false for NaN)
      const double lo = std::fma(a, p10, -hi);
      const double fl = std::floor(hi);
      const double fr = hi - fl;  // exact
      std::uint64_t u = static_cast<std::uint64_t>(fl);
      if (fr > 0.5 || (fr == 0.5 && (lo > 0.0 || (lo == 0.0 && (u & 1u))))) ++u;
      std::uint64_t ip = u / kIPow10[decimals];
      std::uint64_t fp = u - ip * kIPow10[decimals];
      char* p = buf;
      if (std::signbit(value)) *p++ = '-';
      char tmp[24];
      int k = 24;
      do {
        if (ip >= 10) {
          const unsigned r = static_cast<unsigned>(ip % 100);
          ip /= 100;
          tmp[--k] = kPairs[2 * r + 1];
          tmp[--k] = kPairs[2 * r];
          if (ip == 0 && tmp[k] == '0') ++k;  // a leading zero of the last pair
        } else {
          tmp[--k] = static_cast<char>('0' + ip);
          ip = 0;
        }
      } while (ip > 0);
      std::memcpy(p, tmp + k, static_cast<size_t>(24 - k));
      p += 24 - k;
      if (decimals > 0) {
        *p++ = '.';
        char* f = p + decimals;
        int d = decimals;
        while (d >= 2) {
          const unsigned r = static_cast<unsigned>(fp % 100);
          fp /= 100;
          *--f = kPairs[2 * r + 1];
          *--f = kPairs[2 * r];
          d -= 2;
        }
        if (d == 1) *--f = static_cast<char>('0' + fp);
        p += decimals;
      }
      return static_cast<int>(p - buf);
    }
  }
  auto res = std::to_chars(buf, buf + 64, value, std::chars_format::fixed, decimals);
  return static_cast<int>(res.ptr - buf);
}

}  // namespace ldv
