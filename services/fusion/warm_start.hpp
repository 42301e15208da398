#pragma once
// The fusion service's saved state for a warm restart (a small YAML file in its StateDirectory,
// written about once a second). Only what survives a restart gap of a few seconds is used:
// attitude, velocity and the gyro bias (a MEMS turn-on bias of tenths of a deg/s, which the static start
// measured and a restart while moving cannot); position comes from the next GNSS fix.
#include <optional>
#include <string>

#include "estimator/ins/nav_state.hpp"

namespace ldv {

struct WarmState {
  double saved_host_time_s = 0.0;
  est::NavState state;
  est::NavStd std;
  // The gyro bias the filter took out [rad/s, body]: the alignment's turn-on bias plus the filter's estimate.
  // Files saved before it was kept read as zero.
  Vec3 gyro_bias_rad_s = Vec3::Zero();
};

void save_warm_state(const std::string& path, const WarmState& w);  // atomic (write + rename)
// Nothing if the file is missing, unreadable, older than max_age_s, or holds what cannot be a state (a field not
// finite, an attitude std not positive, a pitch beyond +-90 deg, a position or speed no vehicle has, a gyro bias
// beyond any gyro's range); then `why` (when given) says which key and why.
std::optional<WarmState> load_warm_state(const std::string& path, double now_host_s, double max_age_s,
                                         std::string* why = nullptr);

}  // namespace ldv
