#pragma once
// Small facts about a GNSS track shared by the data-driven checks (imu_latency, gnss_velocity_check).
#include <algorithm>
#include <vector>

#include "common/formats/nav_types.hpp"

namespace ldv::est {

// The median of `values` (reordered in place); 0 when empty.
inline double median_in_place(std::vector<double>& values) {
  if (values.empty()) return 0.0;
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

// The nominal interval between fixes: the median of their time differences (robust to outages).
inline double median_fix_interval_s(const std::vector<GnssFix>& gnss) {
  std::vector<double> dts;
  for (size_t k = 1; k < gnss.size(); ++k) dts.push_back(gnss[k].t_s - gnss[k - 1].t_s);
  return median_in_place(dts);
}

}  // namespace ldv::est
