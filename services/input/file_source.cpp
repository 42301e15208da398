#include "services/input/file_source.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "common/logging.hpp"

namespace ldv::io {

FileSource::FileSource(std::string path) : path_(std::move(path)) {}

FileSource::~FileSource() {
  if (fd_ >= 0) ::close(fd_);
}

void FileSource::maintain(double) {
  if (fd_ >= 0 || finished_) return;
  fd_ = ::open(path_.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd_ < 0) {
    ++counters_.open_failures;
    if (!reported_missing_) spdlog::error("{}: {}", describe(), std::strerror(errno));
    reported_missing_ = true;
    return;
  }
  ++counters_.opens;
}

std::size_t FileSource::read_some(std::span<std::uint8_t> buffer, double) {
  if (fd_ < 0 || finished_) return 0;
  const ssize_t n = ::read(fd_, buffer.data(), buffer.size());
  if (n > 0) {
    counters_.bytes += static_cast<std::uint64_t>(n);
    return static_cast<std::size_t>(n);
  }
  if (n < 0 && errno == EINTR) return 0;
  finished_ = true;
  spdlog::info("{}: end of file after {} bytes", describe(), counters_.bytes);
  return 0;
}

}  // namespace ldv::io
