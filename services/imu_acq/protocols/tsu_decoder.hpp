#pragma once
// The ldvnav time-stamp unit's framing (defined with the simulator in
// common/formats/imu_device_frame.hpp: sync A5 5A, type, length, payload, CRC-16/CCITT-FALSE):
// IMU sample frames with a 32-bit free-running counter latched at the sample and 1e-9 rad /
// 1e-9 m/s increments, and PPS latch frames. Frame parsing is the shared FrameDecoder; this adds
// the SI conversion and the lost-sample count from the 16-bit sample sequence numbers.
#include <optional>

#include "common/formats/imu_device_frame.hpp"
#include "services/imu_acq/protocols/imu_device_decoder.hpp"

namespace ldv::imu {

class TsuDecoder : public ImuDeviceDecoder {
 public:
  explicit TsuDecoder(double counter_hz = 10e6) : counter_hz_(counter_hz) {}

  void feed(std::span<const std::uint8_t> bytes) override;
  int counter_bits() const override { return 32; }
  double nominal_counter_hz() const override { return counter_hz_; }
  const DecoderCounters& counters() const override { return counters_; }
  std::uint64_t lost_pps_latches() const { return lost_pps_; }

 private:
  void on_frame(const imu_device::ImuSampleFrame& f);
  void on_frame(const imu_device::PpsLatchFrame& f);

  double counter_hz_;
  imu_device::FrameDecoder frames_;
  DecoderCounters counters_;
  std::optional<std::uint16_t> last_sample_seq_, last_pps_seq_;
  std::uint64_t lost_pps_ = 0;
};

}  // namespace ldv::imu
