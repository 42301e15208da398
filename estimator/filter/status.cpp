#include "estimator/filter/status.hpp"

namespace ldv::est {

std::string describe_status(std::uint32_t bits) {
  static const char* names[] = {"initialized", "gnss_rejected", "gate_resync", "covariance_reset",
                                "state_reset", "zupt_active",   "imu_rejected", "imu_gap",
                                "late_dropped", "gnss_outage",  "measurement_rejected"};
  std::string s;
  for (int i = 0; i < 11; ++i)
    if (bits & (1u << i)) s += (s.empty() ? "" : "|") + std::string(names[i]);
  return s.empty() ? "none" : s;
}

}  // namespace ldv::est
