#pragma once
// TSPI product logic of tspi_pub, kept apart from the bus so it is tested on its own:
// decimates NAV (IMU rate) to the configured TSPI rate on a grid of GPS time, and grades quality.
#include <cmath>
#include <optional>

#include <ldv_lcm/nav_state_t.hpp>
#include <ldv_lcm/tspi_v1_t.hpp>

namespace ldv {

class TspiDecimator {
 public:
  explicit TspiDecimator(double rate_hz) : rate_hz_(rate_hz) {}

  // Returns a TSPI message when this NAV sample is the first at or after the next grid epoch
  // k / rate_hz (GPS seconds of week); otherwise nothing.
  std::optional<ldv_lcm::tspi_v1_t> on_nav(const ldv_lcm::nav_state_t& nav) {
    // 0.1 ms tolerance: NAV epochs carry the IMU stamps, whose last digits jitter (far below an IMU interval).
    const long slot = static_cast<long>(std::floor((nav.gps_sow_s + 1e-4) * rate_hz_));
    if (has_last_slot_ && slot == last_slot_ && nav.gps_week == last_week_) return std::nullopt;
    has_last_slot_ = true;
    last_slot_ = slot;
    last_week_ = nav.gps_week;
    return make_tspi(nav);
  }

  ldv_lcm::tspi_v1_t make_tspi(const ldv_lcm::nav_state_t& nav) {
    ldv_lcm::tspi_v1_t t{};
    t.seq = seq_++;
    t.gps_week = nav.gps_week;
    t.gps_sow_s = nav.gps_sow_s;
    t.lat_deg = nav.lat_deg;
    t.lon_deg = nav.lon_deg;
    t.height_m = nav.height_m;
    for (int i = 0; i < 3; ++i) {
      t.vel_ned_mps[i] = nav.vel_ned_mps[i];
      t.rpy_deg[i] = nav.rpy_deg[i];
      t.pos_std_ned_m[i] = nav.pos_std_ned_m[i];
      t.vel_std_ned_mps[i] = nav.vel_std_ned_mps[i];
      t.att_std_deg[i] = nav.att_std_deg[i];
    }
    t.quality = quality_of(nav);
    return t;
  }

  // 0 invalid, 1 free-inertial, 2 aided (decimetre level or worse), 3 aided at RTK level.
  static int8_t quality_of(const ldv_lcm::nav_state_t& nav) {
    if (nav.mode == 3) return 1;
    if (nav.mode != 2) return 0;
    const double horizontal_std_m = std::hypot(nav.pos_std_ned_m[0], nav.pos_std_ned_m[1]);
    return horizontal_std_m < 0.1 ? 3 : 2;
  }

 private:
  double rate_hz_;
  bool has_last_slot_ = false;
  long last_slot_ = 0;
  int last_week_ = 0;
  int64_t seq_ = 0;
};

}  // namespace ldv
