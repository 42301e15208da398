#pragma once
// The fusion service's saved state for a warm restart (a small YAML file in its StateDirectory,
// written about once a second). Only what survives a restart gap of a few seconds is used:
// attitude and velocity; position comes from the next GNSS fix.
#include <optional>
#include <string>

#include "estimator/ins/nav_state.hpp"

namespace ldv {

struct WarmState {
  double saved_host_time_s = 0.0;
  est::NavState state;
  est::NavStd std;
};

void save_warm_state(const std::string& path, const WarmState& w);  // atomic (write + rename)
// Nothing if the file is missing, unreadable or older than max_age_s.
std::optional<WarmState> load_warm_state(const std::string& path, double now_host_s, double max_age_s);

}  // namespace ldv
