#pragma once
// Where a service's device bytes come from: a serial port, a TCP client or a file. A source never
// throws and never ends the service: a vanished device or connection is closed, counted, and
// reopened by maintain() with exponential backoff. The owner polls fd() together with its other
// descriptors (e.g. the bus) and calls read_some() when it is readable.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

namespace ldv::io {

struct ByteSourceCounters {
  std::uint64_t bytes = 0;
  std::uint64_t opens = 0;        // successful opens / connections
  std::uint64_t open_failures = 0;
  std::uint64_t disconnects = 0;  // read errors, hang-ups, peer closes
};

class ByteSource {
 public:
  virtual ~ByteSource() = default;

  // Opens or reconnects when closed and the backoff delay has passed. Call every loop turn.
  virtual void maintain(double now_s) = 0;
  // The descriptor to poll for input; -1 while closed.
  virtual int fd() const = 0;
  // Reads what is available without blocking: the byte count, 0 when nothing is there (or the
  // source just closed; fd() then says -1).
  virtual std::size_t read_some(std::span<std::uint8_t> buffer, double now_s) = 0;
  // True once a file has been read to its end (streams never finish).
  virtual bool finished() const { return false; }
  // Closed and still expected to deliver: the services' "input down" fault.
  bool down() const { return fd() < 0 && !finished(); }
  // "serial /dev/ttyUSB0 @ 115200", "tcp 127.0.0.1:52001", "file walk.ubx".
  virtual std::string describe() const = 0;

  const ByteSourceCounters& counters() const { return counters_; }

 protected:
  ByteSourceCounters counters_;
};

// Exponential backoff between reconnection attempts: min, 2 min, 4 min ... max; reset on success.
class ReconnectBackoff {
 public:
  ReconnectBackoff(double min_s, double max_s) : min_s_(min_s), max_s_(max_s), delay_s_(min_s) {}
  bool due(double now_s) const { return now_s >= next_attempt_s_; }
  void failed(double now_s) {
    next_attempt_s_ = now_s + delay_s_;
    delay_s_ = delay_s_ * 2.0 > max_s_ ? max_s_ : delay_s_ * 2.0;
  }
  void succeeded() { delay_s_ = min_s_; }
  double delay_s() const { return delay_s_; }

 private:
  double min_s_, max_s_, delay_s_;
  double next_attempt_s_ = 0.0;
};

}  // namespace ldv::io
