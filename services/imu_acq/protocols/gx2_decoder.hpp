#pragma once
// Streaming 3DM-GX2 decoder (records in gx2_frame.hpp). The records carry no sync word: a frame
// starts at a known command byte and is accepted when its checksum is right; on a mismatch the
// hunt moves on by one byte. Rate records (0xC2, 0xC8, 0xCB, 0xCC) become increments over the
// interval since the previous record (timer difference); 0xC3 records are increments already.
// The GX2 has no PPS input: its timer is the sample counter, and PPS comes from elsewhere.
#include <optional>
#include <vector>

#include "services/imu_acq/protocols/gx2_frame.hpp"
#include "services/imu_acq/protocols/imu_device_decoder.hpp"

namespace ldv::imu {

class Gx2Decoder : public ImuDeviceDecoder {
 public:
  // first_interval_s: the interval assumed for the first rate record (no previous timer yet).
  explicit Gx2Decoder(double timer_hz = gx2::kTimerHz, double first_interval_s = 0.01)
      : timer_hz_(timer_hz), first_interval_s_(first_interval_s) {}

  void feed(std::span<const std::uint8_t> bytes) override;
  int counter_bits() const override { return 32; }
  double nominal_counter_hz() const override { return timer_hz_; }
  const DecoderCounters& counters() const override { return counters_; }

 private:
  void on_record(const gx2::Record& r);

  double timer_hz_, first_interval_s_;
  DecoderCounters counters_;
  std::vector<std::uint8_t> pending_;
  std::optional<std::uint32_t> last_timer_;
};

}  // namespace ldv::imu
