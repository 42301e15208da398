#pragma once
// TSPI product logic of tspi_pub, kept apart from the bus so it is tested on its own:
// decimates NAV (IMU rate) to the configured TSPI rate on a grid of GPS time, and grades quality.
#include <cmath>
#include <optional>

#include <ldv_lcm/nav_state_t.hpp>
#include <ldv_lcm/tspi_v1_t.hpp>

#include "common/formats/gnss_solution_checks.hpp"

namespace ldv {

class TspiDecimator {
 public:
  explicit TspiDecimator(double rate_hz) : rate_hz_(rate_hz) {}

  // Returns a TSPI message when this NAV sample is the first at or after the next grid epoch
  // k / rate_hz (GPS seconds of week); otherwise nothing. A NAV that is not usable gives nothing (the
  // caller counts it): a TSPI with NaN is never sent, let alone one marked aided.
  std::optional<ldv_lcm::tspi_v1_t> on_nav(const ldv_lcm::nav_state_t& nav) {
    if (!is_usable(nav)) return std::nullopt;
    // TSPI only goes forward in GPS time (one scale across weeks): a NAV older than the last one sent (fusion
    // replayed an older epoch) would make a receiver's track jump back. Unless NAV as a whole went back (fusion
    // restarted on an input time line that went back) and held for kFollowBack_s of its own time: then TSPI
    // follows, instead of staying silent until the clock catches up.
    const double t_s = nav.gps_week * 604800.0 + nav.gps_sow_s;
    if (has_last_slot_ && t_s <= last_sent_s_) {
      if (!(back_run_ && t_s > back_last_s_)) back_first_s_ = t_s;
      back_run_ = true;
      back_last_s_ = t_s;
      if (t_s - back_first_s_ < kFollowBack_s) return std::nullopt;
      has_last_slot_ = false;  // a new time line
    }
    back_run_ = false;
    // 0.1 ms tolerance: NAV epochs carry the IMU stamps, whose last digits jitter (far below an IMU interval).
    const long slot = static_cast<long>(std::floor((nav.gps_sow_s + 1e-4) * rate_hz_));
    if (has_last_slot_ && slot == last_slot_ && nav.gps_week == last_week_) return std::nullopt;
    has_last_slot_ = true;
    last_slot_ = slot;
    last_week_ = nav.gps_week;
    last_sent_s_ = t_s;
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

  // True when every number a TSPI carries is finite and plausible (the std non-negative, the time inside a
  // plausible week, the height and speed within what gnss_solution_checks allows a receiver): a NaN or a
  // 1e6 m/s anywhere means the estimator's output is not a navigation solution, whatever its mode says.
  static bool is_usable(const ldv_lcm::nav_state_t& nav) {
    const auto finite = [](const auto* v) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); };
    const auto std_ok = [&](const float* v) { return finite(v) && v[0] >= 0 && v[1] >= 0 && v[2] >= 0; };
    const double speed_mps = std::sqrt(nav.vel_ned_mps[0] * nav.vel_ned_mps[0] + nav.vel_ned_mps[1] * nav.vel_ned_mps[1] +
                                       nav.vel_ned_mps[2] * nav.vel_ned_mps[2]);
    return std::isfinite(nav.gps_sow_s) && nav.gps_sow_s >= 0 && nav.gps_sow_s < 604800.0 &&
           nav.gps_week >= gnss::kMinPlausibleGpsWeek && nav.gps_week <= gnss::kMaxPlausibleGpsWeek &&
           std::isfinite(nav.lat_deg) && std::abs(nav.lat_deg) <= 90.0 && std::isfinite(nav.lon_deg) &&
           std::abs(nav.lon_deg) <= 360.0 && std::isfinite(nav.height_m) &&
           nav.height_m >= gnss::kMinPlausibleHeight_m && nav.height_m <= gnss::kMaxPlausibleHeight_m &&
           finite(nav.vel_ned_mps) && speed_mps <= gnss::kMaxPlausibleSpeed_mps && finite(nav.rpy_deg) &&
           std_ok(nav.pos_std_ned_m) && std_ok(nav.vel_std_ned_mps) && std_ok(nav.att_std_deg);
  }

  // 0 invalid (also whenever the NAV is not usable), 1 free-inertial, 2 aided (decimetre level or worse),
  // 3 aided at RTK level.
  static int8_t quality_of(const ldv_lcm::nav_state_t& nav) {
    if (!is_usable(nav)) return 0;
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
  double last_sent_s_ = 0.0;
  static constexpr double kFollowBack_s = 1.0;
  bool back_run_ = false;  // NAV behind the last TSPI sent, since back_first_s_
  double back_first_s_ = 0.0, back_last_s_ = 0.0;
  int64_t seq_ = 0;
};

}  // namespace ldv
