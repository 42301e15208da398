#include "services/imu_acq/protocols/tsu_decoder.hpp"

#include <variant>

namespace ldv::imu {
namespace {
// Frames missing between two 16-bit sequence numbers (a wrap is not a loss).
std::uint64_t missing_between(std::uint16_t previous, std::uint16_t current) {
  return static_cast<std::uint16_t>(current - previous - 1);
}
}  // namespace

void TsuDecoder::feed(std::span<const std::uint8_t> bytes) {
  const auto frames = frames_.push(bytes.data(), bytes.size());
  counters_.bad_checksum = frames_.crc_errors();
  counters_.skipped_bytes = frames_.skipped_bytes();
  for (const auto& f : frames) {
    ++counters_.frames;
    std::visit([this](const auto& frame) { on_frame(frame); }, f);
  }
}

void TsuDecoder::on_frame(const imu_device::ImuSampleFrame& f) {
  if (last_sample_seq_) counters_.lost_samples += missing_between(*last_sample_seq_, f.sequence);
  last_sample_seq_ = f.sequence;
  DeviceSample s;
  s.counter = f.counter;
  for (int i = 0; i < 3; ++i) {
    s.dtheta_b_rad[i] = f.dtheta_lsb[i] * imu_device::kDthetaLsb_rad;
    s.dvel_b_mps[i] = f.dvel_lsb[i] * imu_device::kDvelLsb_mps;
  }
  s.device_error = (f.status & imu_device::kStatusOverRange) != 0;
  if (on_sample_) on_sample_(s);
}

void TsuDecoder::on_frame(const imu_device::PpsLatchFrame& f) {
  if (last_pps_seq_) lost_pps_ += missing_between(*last_pps_seq_, f.sequence);
  last_pps_seq_ = f.sequence;
  if (on_pps_) on_pps_(DevicePpsLatch{f.counter});
}

}  // namespace ldv::imu
