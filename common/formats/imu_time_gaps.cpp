#include "common/formats/imu_time_gaps.hpp"

#include <algorithm>

namespace ldv {

ImuGapSummary find_imu_gaps(const std::vector<ImuIncrement>& imu, const std::vector<long>& lines,
                            double long_gap_factor) {
  ImuGapSummary g;
  if (imu.size() < 2) return g;
  std::vector<double> dts;
  dts.reserve(imu.size());
  for (size_t i = 1; i < imu.size(); ++i) dts.push_back(imu[i].t_s - imu[i - 1].t_s);
  std::nth_element(dts.begin(), dts.begin() + dts.size() / 2, dts.end());
  g.nominal_dt_s = dts[dts.size() / 2];
  for (size_t i = 1; i < imu.size(); ++i) {
    const double dt = imu[i].t_s - imu[i - 1].t_s;
    if (dt > 1.5 * g.nominal_dt_s) ++g.gaps;
    if (dt > long_gap_factor * g.nominal_dt_s)
      g.long_gaps.push_back({imu[i - 1].t_s, imu[i].t_s, lines.empty() ? static_cast<long>(i + 1) : lines[i]});
    g.longest_gap_s = std::max(g.longest_gap_s, dt);
  }
  return g;
}

}  // namespace ldv
