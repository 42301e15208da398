#include "services/input/serial_port.hpp"

#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "common/logging.hpp"

namespace ldv::io {

unsigned baud_constant(int baud) {
  switch (baud) {
    case 9600: return B9600;
    case 19200: return B19200;
    case 38400: return B38400;
    case 57600: return B57600;
    case 115200: return B115200;
    case 230400: return B230400;
    case 460800: return B460800;
    case 921600: return B921600;
    default: return 0;
  }
}

SerialPort::SerialPort(SerialOptions options)
    : options_(std::move(options)), backoff_(options_.reopen_min_s, options_.reopen_max_s) {}

SerialPort::~SerialPort() {
  if (fd_ >= 0) ::close(fd_);
}

std::string SerialPort::describe() const {
  return "serial " + options_.device + " @ " + std::to_string(options_.baud);
}

void SerialPort::maintain(double now_s) {
  if (fd_ >= 0 || !backoff_.due(now_s)) return;
  // O_NOCTTY: a pty or modem line must never become our controlling terminal (SIGHUP on close).
  const int fd = ::open(options_.device.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  std::string error;
  termios tio{};
  const unsigned speed = baud_constant(options_.baud);
  if (fd < 0) {
    error = std::strerror(errno);
  } else if (speed == 0) {
    error = "unsupported baud rate " + std::to_string(options_.baud);
  } else if (::tcgetattr(fd, &tio) != 0) {
    error = std::string("not a terminal: ") + std::strerror(errno);
  } else {
    ::cfmakeraw(&tio);
    tio.c_cflag |= CLOCAL | CREAD;
    tio.c_cflag &= ~(CRTSCTS | CSTOPB | PARENB);
    tio.c_cc[VMIN] = 0;
    tio.c_cc[VTIME] = 0;
    ::cfsetispeed(&tio, speed);
    ::cfsetospeed(&tio, speed);
    if (::tcsetattr(fd, TCSANOW, &tio) != 0) error = std::string("tcsetattr: ") + std::strerror(errno);
    // Bytes the driver buffered before this open (a restarted service) are stale: start from the live stream.
    else ::tcflush(fd, TCIFLUSH);
  }
  if (!error.empty()) {
    if (fd >= 0) ::close(fd);
    ++counters_.open_failures;
    if (error != last_error_) spdlog::warn("{}: cannot open: {} (retrying)", describe(), error);
    last_error_ = error;
    backoff_.failed(now_s);
    return;
  }
  fd_ = fd;
  last_error_.clear();
  ++counters_.opens;
  backoff_.succeeded();
  spdlog::info("{}: open", describe());
}

void SerialPort::close_port(double now_s) {
  ::close(fd_);
  fd_ = -1;
  ++counters_.disconnects;
  backoff_.failed(now_s);
}

std::size_t SerialPort::read_some(std::span<std::uint8_t> buffer, double now_s) {
  if (fd_ < 0) return 0;
  const ssize_t n = ::read(fd_, buffer.data(), buffer.size());
  if (n > 0) {
    counters_.bytes += static_cast<std::uint64_t>(n);
    return static_cast<std::size_t>(n);
  }
  if (n < 0 && (errno == EAGAIN || errno == EINTR)) return 0;
  // A raw tty with VMIN = VTIME = 0 reads 0 when empty; only a hang-up (pty master closed,
  // USB adapter gone) makes it an end of input.
  if (n == 0) {
    pollfd p{fd_, POLLIN, 0};
    if (::poll(&p, 1, 0) <= 0 || !(p.revents & (POLLHUP | POLLERR | POLLNVAL))) return 0;
    errno = EIO;
  }
  // EIO: the pty master closed or the USB adapter went away. Reopen later.
  spdlog::warn("{}: {} (reopening)", describe(), std::strerror(errno));
  close_port(now_s);
  return 0;
}

bool SerialPort::write_all(std::span<const std::uint8_t> bytes) {
  if (fd_ < 0) return false;
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd_, bytes.data() + done, bytes.size() - done);
    if (n < 0 && (errno == EAGAIN || errno == EINTR)) continue;
    if (n <= 0) return false;
    done += static_cast<std::size_t>(n);
  }
  return true;
}

std::size_t SerialPort::write_some(std::span<const std::uint8_t> bytes, double now_s) {
  if (fd_ < 0 || bytes.empty()) return 0;
  const ssize_t n = ::write(fd_, bytes.data(), bytes.size());
  if (n > 0) return static_cast<std::size_t>(n);
  if (n < 0 && (errno == EAGAIN || errno == EINTR)) return 0;
  spdlog::warn("{}: {} (reopening)", describe(), n < 0 ? std::strerror(errno) : "nothing written");
  close_port(now_s);
  return 0;
}

}  // namespace ldv::io
