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

// The low-level fast path under read_numeric_table, for readers of very long files (imu.txt): the file
// is read in 1 MiB blocks into one reused buffer (no per-line copy or allocation, and no page faults on a
// whole-file buffer: they cost more than the parsing on a virtual machine), lines handed out as views.
class TextFileLines {
 public:
  explicit TextFileLines(const std::string& path);  // throws InputError if it cannot be opened/read
  ~TextFileLines();
  TextFileLines(const TextFileLines&) = delete;
  TextFileLines& operator=(const TextFileLines&) = delete;
  // Next line without its '\n' (a trailing '\r' is kept: parse_numeric_line treats it as a separator).
  // The view is valid until the next call.
  bool next(std::string_view& line);
  long line_number() const { return line_no_; }  // of the line last returned (1-based)
  long size_bytes() const { return file_size_; } // -1 when unknown (a pipe)
  // Expected number of lines from the file size and the lines of the first block (for reserve()).
  size_t estimated_lines();
  const std::string& path() const { return path_; }

 private:
  bool refill();
  std::string path_;
  std::FILE* file_ = nullptr;
  long file_size_ = -1;
  std::unique_ptr<char[]> buf_;
  size_t cap_ = 0, begin_ = 0, end_ = 0;
  bool eof_ = false;
  long line_no_ = 0;
};

// Parses every field of one line as read_numeric_table does (same checks and messages): stores the first
// `max_store` values in `values`, checks the others, and returns the number of fields (0: empty or comment).
int parse_numeric_line(std::string_view line, double* values, int max_store, const std::string& path, long line_no);

// The message read_numeric_table gives for a wrong column count.
[[noreturn]] void throw_column_count(const std::string& path, long line_no, int min_columns, int max_columns, int found);

// Formats a double into buf with `decimals` fixed decimals (0..17); returns the number of chars written.
// Exact integer arithmetic for |value| * 10^decimals < 2^52 (the same digits as std::to_chars),
// std::to_chars otherwise. Several times faster than printf: the full-rate
// outputs call it ~2 million times per 900 s file.
int format_fixed(char* buf, double value, int decimals);

}  // namespace ldv
