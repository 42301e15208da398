#include "services/input/file_source.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "common/logging.hpp"

namespace ldv::io {

FileSource::FileSource(std::string path) : path_(std::move(path)) {}

FileSource::~FileSource() {
  if (fd_ >= 0) ::close(fd_);
}

void FileSource::maintain(double now_s) {
  if (fd_ >= 0 || finished_ || now_s < reopen_at_s_) return;
  // Non-blocking: a FIFO with no writer yet opened without O_NONBLOCK held the service before READY (issue 46).
  fd_ = ::open(path_.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd_ < 0) {
    ++counters_.open_failures;
    if (!reported_missing_) spdlog::error("{}: {}", describe(), std::strerror(errno));
    reported_missing_ = true;
    return;
  }
  struct stat st {};
  if (::fstat(fd_, &st) == 0 && S_ISDIR(st.st_mode)) {
    // A folder read as "end of file after 0 bytes": said for what it is, and tried again (it may be replaced).
    ::close(fd_);
    fd_ = -1;
    ++counters_.open_failures;
    if (!reported_missing_) spdlog::error("{}: is a folder; expected a file, a FIFO or a device", describe());
    reported_missing_ = true;
    return;
  }
  fifo_ = S_ISFIFO(st.st_mode);
  ++counters_.opens;
}

std::size_t FileSource::read_some(std::span<std::uint8_t> buffer, double now_s) {
  if (fd_ < 0 || finished_) return 0;
  const ssize_t n = ::read(fd_, buffer.data(), buffer.size());
  if (n > 0) {
    counters_.bytes += static_cast<std::uint64_t>(n);
    return static_cast<std::size_t>(n);
  }
  if (n < 0 && (errno == EINTR || errno == EAGAIN)) return 0;  // nothing yet (a FIFO's writer has not written)
  if (n == 0 && fifo_) {
    // A FIFO's writer closed (or has not opened yet): not the end of a recording; opened again for the next one.
    ::close(fd_);
    fd_ = -1;
    reopen_at_s_ = now_s + kFifoReopen_s;  // not at once: a FIFO without a writer is readable (hang-up) at once
    return 0;
  }
  finished_ = true;
  spdlog::info("{}: end of file after {} bytes", describe(), counters_.bytes);
  return 0;
}

}  // namespace ldv::io
