#pragma once
// Delimited text tables as people publish them (a logger's CSV, a spreadsheet export, a whitespace listing): lines
// of preamble ("Fs,100", "Logging Type,1"), a header naming the columns, then the rows. The layout is read from the
// file itself, over its first kSniffLines lines:
//  - the separator: a spreadsheet's `sep=X` first line, else the candidate (',' ';' tab, runs of spaces) that splits
//    the most lines into one field count above 1;
//  - the rows: from the first line with that field count whose numeric columns are those of the line after it;
//  - the header: the line just before the rows when it has their field count and text where they have numbers
//    (none: columns are known by their 1-based index only);
//  - a field in double quotes loses them; with ';' or tab separators a decimal comma ("0,25") is read as a point
//    when the rows hold such numbers and no field with a point.
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace ldv {

struct TableLayout {
  char separator = ',';             // ' ' stands for runs of spaces and tabs
  bool decimal_comma = false;       // numbers written 0,25
  std::vector<std::string> header;  // the column names; empty when the file names none
  long header_line = 0;             // 1-based; 0 without a header
  long first_row_line = 0;          // 1-based line of the first data row
  int columns = 0;                  // fields per data row
  // "comma-separated, 6 columns, header on line 5 (ax, ay, ...), rows from line 6"
  std::string describe() const;
};

// Reads the first lines of `path` for its layout. InputError naming the file when it has no rows.
TableLayout sniff_table_layout(const std::string& path);

// The 0-based column a user names in `key` (their configuration key, for the message): a header name (exact, else
// the only case-insensitive match) or a 1-based index written as a whole number. InputError naming the file, the key
// and the header's names otherwise.
int table_column(const TableLayout& layout, const std::string& name_or_index, const std::string& path,
                 const std::string& key);

// Splits one line as the layout says into `fields` (views into the line, quotes removed).
void split_table_line(std::string_view line, const TableLayout& layout, std::vector<std::string_view>& fields);

// Calls on_row(line_number, fields) for every line from the first data row on, except empty lines and comments
// ('#'); a line with another field count is passed too (the caller counts what it drops).
void for_each_table_row(const std::string& path, const TableLayout& layout,
                        const std::function<void(long, const std::vector<std::string_view>&)>& on_row);

// A field as a finite number (a decimal comma when the layout has one); false for text, NaN or inf.
bool parse_table_number(std::string_view field, const TableLayout& layout, double& value);

}  // namespace ldv
