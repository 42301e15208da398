#include "common/io/text_file_lines.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

namespace ldv {
namespace {

// What a non-regular file is, for the message.
const char* kind_of(mode_t m) {
  if (S_ISDIR(m)) return "a directory";
  if (S_ISCHR(m)) return "a character device";
  if (S_ISBLK(m)) return "a block device";
  if (S_ISSOCK(m)) return "a socket";
  return "not a regular file";
}

void check_mode(const std::string& path, int fd) {
  struct stat st {};
  if (::fstat(fd, &st) != 0) throw InputError(path, 0, std::string("cannot stat: ") + std::strerror(errno));
  if (!S_ISREG(st.st_mode) && !S_ISFIFO(st.st_mode))
    throw InputError(path, 0, std::string("is ") + kind_of(st.st_mode) + ": expected a regular text file");
}

std::string too_long(size_t max_bytes) {
  return "line longer than " + std::to_string(max_bytes) + " bytes: expected a text file (binary or wrong file?)";
}

}  // namespace

void require_regular_file_or_pipe(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) throw InputError(path, 0, std::string("cannot open: ") + std::strerror(errno));
  if (!S_ISREG(st.st_mode) && !S_ISFIFO(st.st_mode))
    throw InputError(path, 0, std::string("is ") + kind_of(st.st_mode) + ": expected a regular file");
}

std::string read_small_text_file(const std::string& path, size_t max_bytes) {
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!f) throw InputError(path, 0, std::string("cannot open file for reading: ") + std::strerror(errno));
  check_mode(path, ::fileno(f.get()));
  std::string text;
  char block[65536];
  for (;;) {
    const size_t got = std::fread(block, 1, sizeof block, f.get());
    if (got == 0) break;
    if (text.size() + got > max_bytes)
      throw InputError(path, 0, "larger than " + std::to_string(max_bytes) + " bytes: expected a small text file");
    text.append(block, got);
  }
  if (std::ferror(f.get())) throw InputError(path, 0, "read error");
  return text;
}

TextFileLines::TextFileLines(const std::string& path, size_t max_line_bytes) : path_(path), max_line_(max_line_bytes) {
  file_ = std::fopen(path.c_str(), "rb");
  if (!file_) throw InputError(path, 0, std::string("cannot open file for reading: ") + std::strerror(errno));
  try {
    check_mode(path, ::fileno(file_));
  } catch (...) {
    std::fclose(file_);
    file_ = nullptr;
    throw;
  }
  struct stat st {};
  if (::fstat(::fileno(file_), &st) == 0 && S_ISREG(st.st_mode)) file_size_ = static_cast<long>(st.st_size);
  // Room for a whole line of the maximum length, so the buffer never grows.
  cap_ = std::max(static_cast<size_t>(1) << 20, 2 * max_line_ + 2);
  buf_.reset(new char[cap_]);
}

TextFileLines::~TextFileLines() {
  if (file_) std::fclose(file_);
}

bool TextFileLines::refill() {
  if (eof_) return false;
  // Keep the unfinished line (at most max_line_ bytes, see next()) at the front.
  const size_t rest = end_ - begin_;
  if (begin_ > 0) std::memmove(buf_.get(), buf_.get() + begin_, rest);
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
      if (len > max_line_) throw InputError(path_, line_no_ + 1, too_long(max_line_));
      line = std::string_view(b, len);
      line_begin_ = consumed_;
      line_len_ = len;
      line_terminated_ = true;
      begin_ += len + 1;
      consumed_ += len + 1;
      ++line_no_;
      return true;
    }
    if (end_ - begin_ > max_line_) throw InputError(path_, line_no_ + 1, too_long(max_line_));
    if (!refill()) break;
  }
  if (begin_ < end_) {  // an unterminated last line
    line = std::string_view(buf_.get() + begin_, end_ - begin_);
    line_begin_ = consumed_;
    line_len_ = end_ - begin_;
    line_terminated_ = false;
    consumed_ += end_ - begin_;
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

}  // namespace ldv
