#include "common/io/output_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "common/io/input_error.hpp"
#include "common/logging.hpp"

namespace ldv {
namespace {
[[noreturn]] void fail(const std::string& path, const char* what, int err) {
  throw InputError(path, 0, std::string(what) + ": " + std::strerror(err) + " (the file is incomplete)");
}
}  // namespace

namespace {
// fopen of a FIFO blocks until a reader opens it: `ldv nav --out FIFO` with nobody reading hung for ever. A FIFO
// is opened without blocking first (ENXIO: no reader), then written as any file.
std::FILE* open_for_writing(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0 && S_ISFIFO(st.st_mode)) {
    const int fd = ::open(path.c_str(), O_WRONLY | O_NONBLOCK);
    if (fd < 0) {
      if (errno == ENXIO) throw InputError(path, 0, "a FIFO that nothing reads: start its reader first");
      return nullptr;
    }
    ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
    return ::fdopen(fd, "wb");
  }
  return std::fopen(path.c_str(), "wb");
}
}  // namespace

OutputFile::OutputFile(const std::string& path) : path_(path), file_(open_for_writing(path)) {
  if (!file_) throw InputError(path, 0, std::string("cannot open file for writing: ") + std::strerror(errno));
}

OutputFile::~OutputFile() {
  if (!file_) return;
  const bool ok = std::fflush(file_) == 0 && !std::ferror(file_);
  const bool closed = std::fclose(file_) == 0;
  if (!ok || !closed) spdlog::error("{}: write failed while closing after an error: the file is incomplete", path_);
}

void OutputFile::write(const char* data, size_t n) {
  if (n == 0) return;
  if (!file_) throw InputError(path_, 0, "write after close");
  if (std::fwrite(data, 1, n, file_) != n) fail(path_, "write failed", errno);
}

void OutputFile::close() {
  if (!file_) return;
  std::FILE* f = file_;
  file_ = nullptr;
  const bool flushed = std::fflush(f) == 0 && !std::ferror(f);
  const int flush_err = errno;
  if (std::fclose(f) != 0) fail(path_, "close failed", errno);
  if (!flushed) fail(path_, "write failed", flush_err);
}

void close_checked(std::FILE* f, const std::string& path) {
  const bool flushed = std::fflush(f) == 0 && !std::ferror(f);
  const int flush_err = errno;
  if (std::fclose(f) != 0) fail(path, "close failed", errno);
  if (!flushed) fail(path, "write failed", flush_err);
}

void close_checked(std::ofstream& out, const std::string& path) {
  out.flush();
  const bool ok = static_cast<bool>(out);
  const int err = errno;
  out.close();
  if (!ok) fail(path, "write failed", err);
  if (out.fail()) fail(path, "close failed", errno);
}

}  // namespace ldv
