#pragma once
// The one line reader for text input (KF-GINS files, tagged CSV, calibration logs, side files): bounded.
// A line longer than max_line_bytes (64 KiB: a hundred times the longest line any of our formats writes)
// raises InputError naming file and line, so `/dev/zero` or a binary file given as text ends in a clear
// error, not in unbounded memory. Only regular files and pipes are accepted (a directory, a device or a
// socket is refused at open): a pipe is still bounded per line.
#include <cstdio>
#include <memory>
#include <string>
#include <string_view>

#include "common/io/input_error.hpp"

namespace ldv {

constexpr size_t kMaxTextLineBytes = static_cast<size_t>(64) << 10;

// Throws InputError naming the path if it is not a regular file or a pipe (e.g. /dev/zero, a directory).
void require_regular_file_or_pipe(const std::string& path);

// A whole small text file (a YAML configuration), refused beyond max_bytes (and for non-regular files).
std::string read_small_text_file(const std::string& path, size_t max_bytes = static_cast<size_t>(16) << 20);

// Reads a file in 1 MiB blocks into one reused buffer (no per-line copy or allocation, and no page faults on a
// whole-file buffer: they cost more than the parsing on a virtual machine), lines handed out as views.
class TextFileLines {
 public:
  // Throws InputError if the file cannot be opened or is not a regular file or a pipe.
  explicit TextFileLines(const std::string& path, size_t max_line_bytes = kMaxTextLineBytes);
  ~TextFileLines();
  TextFileLines(const TextFileLines&) = delete;
  TextFileLines& operator=(const TextFileLines&) = delete;
  // Next line without its '\n' (a trailing '\r' is kept: parse_numeric_line treats it as a separator).
  // The view is valid until the next call. Throws InputError on a line longer than max_line_bytes.
  bool next(std::string_view& line);
  long line_number() const { return line_no_; }  // of the line last returned (1-based)
  // Byte offset in the file of the first byte of the line last returned, and of the byte after it (its '\n').
  unsigned long long line_begin_offset() const { return line_begin_; }
  unsigned long long line_end_offset() const { return line_begin_ + line_len_; }
  bool last_line_terminated() const { return line_terminated_; }  // false: the file ended without '\n'
  long size_bytes() const { return file_size_; }                  // -1 when unknown (a pipe)
  // Expected number of lines from the file size and the lines of the first block (for reserve()).
  size_t estimated_lines();
  const std::string& path() const { return path_; }

 private:
  bool refill();
  std::string path_;
  std::FILE* file_ = nullptr;
  long file_size_ = -1;
  size_t max_line_;
  std::unique_ptr<char[]> buf_;
  size_t cap_ = 0, begin_ = 0, end_ = 0;
  unsigned long long consumed_ = 0;  // file offset of buf_[begin_]
  unsigned long long line_begin_ = 0;
  size_t line_len_ = 0;
  bool line_terminated_ = true;
  bool eof_ = false;
  long line_no_ = 0;
};

}  // namespace ldv
