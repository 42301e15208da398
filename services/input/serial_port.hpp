#pragma once
// A serial port in raw mode (termios: 8N1, no flow control, no echo, no line editing) at a
// configured baud rate. Works unchanged on a pty slave, which is how the simulator and the tests
// drive it. Reopened with backoff when the device disappears (USB unplug, pty master closed).
#include <string>

#include "services/input/byte_source.hpp"

namespace ldv::io {

struct SerialOptions {
  std::string device = "/dev/ttyUSB0";
  int baud = 115200;
  double reopen_min_s = 0.5;
  double reopen_max_s = 5.0;
};

class SerialPort : public ByteSource {
 public:
  explicit SerialPort(SerialOptions options);
  ~SerialPort() override;
  SerialPort(const SerialPort&) = delete;
  SerialPort& operator=(const SerialPort&) = delete;

  void maintain(double now_s) override;
  int fd() const override { return fd_; }
  std::size_t read_some(std::span<std::uint8_t> buffer, double now_s) override;
  std::string describe() const override;
  // Writes a command to the device (e.g. to start a 3DM-GX2's continuous mode). False if closed.
  bool write_all(std::span<const std::uint8_t> bytes);
  // Writes what the driver takes now without waiting (an output stream whose reader may stall: a service must not
  // freeze on it): the bytes written, 0 when closed or full; a hang-up closes the port for a later reopen.
  std::size_t write_some(std::span<const std::uint8_t> bytes, double now_s);

 private:
  void close_port(double now_s);

  SerialOptions options_;
  ReconnectBackoff backoff_;
  int fd_ = -1;
  std::string last_error_;
};

// The termios speed constant for a baud rate; 0 when the rate is not a standard one.
unsigned baud_constant(int baud);

}  // namespace ldv::io
