#pragma once
// Fast, strict reading of whitespace/comma separated numeric text files (KF-GINS, RTKLIB, CSV).
// Every value is checked: non-numeric text, NaN/inf and wrong column counts raise InputError with
// the file name and line number.
#include <charconv>
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

// Formats a double into buf with `decimals` fixed decimals; returns the number of chars written.
// std::to_chars based: several times faster than printf for the full-rate outputs.
int format_fixed(char* buf, double value, int decimals);

}  // namespace ldv
