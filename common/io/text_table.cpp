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

std::string FieldError::message() const {
  return "column " + std::to_string(column) + ": expected a " + (non_finite ? "finite number" : "number") +
         ", found '" + text + "'";
}

int scan_numeric_line(std::string_view line, double* values, int max_store, FieldError* error) {
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
      if (error) {
        const char* fe = field;
        while (fe < end && !is_separator(*fe)) ++fe;
        error->column = n + 1;
        // from_chars reports out-of-range (1e999) as an error with the whole field consumed: not finite either.
        error->non_finite = (ec == std::errc() || ec == std::errc::result_out_of_range) && (ptr == fe);
        error->text.assign(field, std::min<size_t>(static_cast<size_t>(fe - field), 40));
      }
      return -1;
    }
    if (n < max_store) values[n] = v;
    ++n;
    p = ptr;
  }
  return n;
}

int parse_numeric_line(std::string_view line, double* values, int max_store, const std::string& path, long line_no) {
  FieldError err;
  const int n = scan_numeric_line(line, values, max_store, &err);
  if (n < 0) throw InputError(path, line_no, err.message());
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
  // Everything below writes at most kFormatFixedMaxChars and checks the conversion (a value too large for
  // the buffer once left the buffer's old bytes in the file).
  if (std::isnan(value)) {
    std::memcpy(buf, "nan", 3);
    return 3;
  }
  if (std::isinf(value)) {
    if (value < 0) {
      std::memcpy(buf, "-inf", 4);
      return 4;
    }
    std::memcpy(buf, "inf", 3);
    return 3;
  }
  decimals = std::clamp(decimals, 0, 17);
  const bool fits_fixed = std::fabs(value) < 1e21;  // at most 21 integer digits
  auto res = fits_fixed ? std::to_chars(buf, buf + kFormatFixedMaxChars, value, std::chars_format::fixed, decimals)
                        : std::to_chars(buf, buf + kFormatFixedMaxChars, value, std::chars_format::scientific, 17);
  if (res.ec != std::errc()) {  // cannot happen with the bounds above; never hand out unwritten bytes
    std::memcpy(buf, "nan", 3);
    return 3;
  }
  return static_cast<int>(res.ptr - buf);
}

}  // namespace ldv
