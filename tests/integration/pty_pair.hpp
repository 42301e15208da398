#pragma once
// A pseudo-terminal for driving a service's serial port from a test: the test writes device bytes
// to the master, the service opens slave_path() as its serial device. The slave is set raw before
// any byte is written so the line discipline never echoes or translates them.
#include <pty.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace ldv::test {

class PtyPair {
 public:
  PtyPair() {
    char name[256];
    if (::openpty(&master_, &slave_, name, nullptr, nullptr) != 0) throw std::runtime_error("openpty failed");
    slave_path_ = name;
    termios tio{};
    ::tcgetattr(slave_, &tio);
    ::cfmakeraw(&tio);
    ::tcsetattr(slave_, TCSANOW, &tio);
  }
  ~PtyPair() {
    if (slave_ >= 0) ::close(slave_);
    if (master_ >= 0) ::close(master_);
  }
  PtyPair(const PtyPair&) = delete;
  PtyPair& operator=(const PtyPair&) = delete;

  const std::string& slave_path() const { return slave_path_; }
  int master_fd() const { return master_; }  // what the service writes to its serial port is read here
  // Blocks while the pty buffer is full (the reader sets the pace). False on error.
  bool write_all(const std::uint8_t* data, std::size_t n) {
    std::size_t done = 0;
    while (done < n) {
      const ssize_t w = ::write(master_, data + done, n - done);
      if (w < 0 && errno == EINTR) continue;
      if (w <= 0) return false;
      done += static_cast<std::size_t>(w);
    }
    return true;
  }
  bool write_all(const std::string& s) { return write_all(reinterpret_cast<const std::uint8_t*>(s.data()), s.size()); }

 private:
  int master_ = -1, slave_ = -1;
  std::string slave_path_;
};

}  // namespace ldv::test
