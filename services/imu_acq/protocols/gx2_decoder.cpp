#include "services/imu_acq/protocols/gx2_decoder.hpp"

namespace ldv::imu {

void Gx2Decoder::feed(std::span<const std::uint8_t> bytes) {
  pending_.insert(pending_.end(), bytes.begin(), bytes.end());
  std::size_t i = 0;
  while (i < pending_.size()) {
    const auto n = gx2::record_bytes(pending_[i]);
    if (!n) {
      ++counters_.skipped_bytes;
      ++i;
      continue;
    }
    if (pending_.size() - i < *n) break;  // wait for the rest
    const auto record = gx2::parse_record(std::span(pending_).subspan(i, *n));
    if (!record) {
      ++counters_.bad_checksum;
      ++counters_.skipped_bytes;
      ++i;
      continue;
    }
    ++counters_.frames;
    on_record(*record);
    i += *n;
  }
  pending_.erase(pending_.begin(), pending_.begin() + static_cast<std::ptrdiff_t>(i));
}

void Gx2Decoder::on_record(const gx2::Record& r) {
  DeviceSample s;
  s.counter = r.timer;
  if (r.is_delta()) {
    for (int i = 0; i < 3; ++i) {
      s.dtheta_b_rad[i] = r.first[i];
      s.dvel_b_mps[i] = r.second[i] * gx2::kStandardGravity_mps2;
    }
  } else {
    // Rates held over the interval: exact for constant rates, first order otherwise.
    const double dt_s = last_timer_ ? static_cast<std::uint32_t>(r.timer - *last_timer_) / timer_hz_ : first_interval_s_;
    for (int i = 0; i < 3; ++i) {
      s.dtheta_b_rad[i] = r.first[i] * dt_s;
      s.dvel_b_mps[i] = r.second[i] * gx2::kStandardGravity_mps2 * dt_s;
    }
  }
  last_timer_ = r.timer;
  // A NaN or infinity passes the record's 16-bit sum: no measurement, but its timer is good. Flagged as the
  // device's error (imu_acq's status bit 1: navigation bridges it as a lost sample), its increments zeroed.
  if (!s.dtheta_b_rad.allFinite() || !s.dvel_b_mps.allFinite()) {
    s.device_error = true;
    s.dtheta_b_rad.setZero();
    s.dvel_b_mps.setZero();
  }
  if (on_sample_) on_sample_(s);
}

}  // namespace ldv::imu
