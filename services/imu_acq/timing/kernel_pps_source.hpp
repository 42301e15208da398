#pragma once
// Host-side PPS through the Linux kernel PPS API (RFC 2783, /dev/ppsN, <sys/timepps.h> from
// pps-tools): the kernel time-stamps the assert edge in its interrupt handler (CLOCK_REALTIME).
// The stamp is the host clock, not an IMU counter: feed it to PpsTimeFit with counter_bits = 64
// and nominal_counter_hz = 1e9 to map host nanoseconds to GPS time. Missed pulses show as gaps in
// the assert sequence number.
#include <cstdint>
#include <optional>
#include <string>

namespace ldv::timing {

struct KernelPpsEvent {
  std::uint64_t sequence = 0;      // kernel's assert count
  std::int64_t assert_time_ns = 0; // CLOCK_REALTIME of the assert edge [ns since the Unix epoch]
};

class KernelPpsSource {
 public:
  // Opens the device and selects assert capture. nullopt with `error` set when the path is not
  // a PPS device (or the kernel has no PPS support).
  static std::optional<KernelPpsSource> open(const std::string& device, std::string& error);

  KernelPpsSource(KernelPpsSource&& other) noexcept;
  KernelPpsSource& operator=(KernelPpsSource&&) = delete;
  KernelPpsSource(const KernelPpsSource&) = delete;
  ~KernelPpsSource();

  // Waits up to timeout_s for the next assert event (needs PPS_CANWAIT). nullopt on timeout or
  // error (`error` set on error, empty on timeout). Events already seen are not returned twice.
  std::optional<KernelPpsEvent> fetch(double timeout_s, std::string& error);

 private:
  explicit KernelPpsSource(int fd) : fd_(fd) {}
  int fd_ = -1;
  std::optional<std::uint64_t> last_sequence_;
};

}  // namespace ldv::timing
