#pragma once
// Fast, strict reading of whitespace/comma separated numeric text files (KF-GINS, RTKLIB, CSV).
// Every value is checked: non-numeric text, NaN/inf and wrong column counts raise InputError with
// the file name and line number.
#include <charconv>
#include <cstdio>
#include <memory>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "common/io/input_error.hpp"
#include "common/io/text_file_lines.hpp"

namespace ldv {

// Splits a line on spaces, tabs and commas into fields (no allocation: views into the line).
void split_fields(std::string_view line, std::vector<std::string_view>& fields);

// Parses a finite double; throws InputError naming file, line and column on failure.
double parse_double(std::string_view field, const std::string& file, long line, int column);

// Calls on_row(line_number, values) for every non-empty, non-comment ('#' or '%') line.
// Rows whose column count is not in [min_columns, max_columns] raise InputError.
// Throws InputError if the file cannot be opened.
void read_numeric_table(const std::string& path, int min_columns, int max_columns,
                        const std::function<void(long, const std::vector<double>&)>& on_row);

// The line reader under read_numeric_table (bounded line length): common/io/text_file_lines.hpp.

// Why scan_numeric_line refused a line: the 1-based column, whether the field was a number that is not
// finite (nan, inf, 1e999), and the field's text (cut to 40 characters) for the message.
struct FieldError {
  int column = 0;
  bool non_finite = false;
  std::string text;
  std::string message() const;  // "column 4: expected a number, found 'abc'"
};

// Like parse_numeric_line, without throwing (for readers that count and drop bad records): returns -1 and fills
// *error when a field is not a finite number.
int scan_numeric_line(std::string_view line, double* values, int max_store, FieldError* error);

// Parses every field of one line as read_numeric_table does (same checks and messages): stores the first
// `max_store` values in `values`, checks the others, and returns the number of fields (0: empty or comment).
int parse_numeric_line(std::string_view line, double* values, int max_store, const std::string& path, long line_no);

// The message read_numeric_table gives for a wrong column count.
[[noreturn]] void throw_column_count(const std::string& path, long line_no, int min_columns, int max_columns, int found);

// Longest text format_fixed writes (sign, 21 integer digits, point, 17 decimals; or "-inf").
constexpr int kFormatFixedMaxChars = 48;

// Formats a double into buf (room for kFormatFixedMaxChars) with `decimals` fixed decimals (clamped to
// 0..17); returns the number of chars written, never more than kFormatFixedMaxChars. Exact integer arithmetic
// for |value| * 10^decimals < 2^52 (the same digits as std::to_chars), std::to_chars otherwise. Beyond
// |value| >= 1e21 the fixed form would need up to 309 digits: such a value is written in scientific form
// (%.17e: still a number every reader parses back exactly). Non-finite values are written as nan, inf, -inf
// (printf's tokens); writers whose format has no place for them (the .nav) refuse them before calling this.
// Several times faster than printf: the full-rate outputs call it ~2 million times per 900 s file.
int format_fixed(char* buf, double value, int decimals);

}  // namespace ldv
