#include "toolbox/assess/outage_smoothed.hpp"

#include <algorithm>
#include <cmath>

#include "estimator/filter/nav_filter.hpp"
#include "estimator/run/run_navigation.hpp"
#include "estimator/smooth/rts_recorder.hpp"
#include "toolbox/assess/nav_difference.hpp"

namespace ldv::assess {

std::vector<SmoothedGap> smooth_through_gaps(const std::vector<ImuIncrement>& imu, const std::vector<GnssFix>& gnss,
                                             const KfGinsConfig& cfg, const est::FilterOptions& options,
                                             const std::vector<OutageWindow>& windows, const NavSeries& reference,
                                             const std::vector<est::ObservationPtr>& others, double eval_period_s,
                                             bool reference_on_gps_time) {
  auto gap_of = [&](double t_s) {
    for (std::size_t g = 0; g < windows.size(); ++g)
      if (t_s > windows[g].start_s && t_s <= windows[g].start_s + windows[g].length_s) return static_cast<int>(g);
    return -1;
  };
  std::vector<GnssFix> cut;
  for (const GnssFix& f : gnss)
    if (gap_of(f.t_s) < 0) cut.push_back(f);

  est::NavFilter filter(options);
  est::RtsRecorder recorder(filter);
  filter.set_observer(&recorder);
  est::RunCallbacks cb;
  cb.on_epoch = [&](const est::NavFilter& f) { recorder.add_row(f, 0); };
  est::run_navigation(imu, cut, cfg, filter, cb, nullptr, &others);
  const est::SmoothedRun run = recorder.smooth();
  // A row at IMU epoch t is GPS time t + time_offset (the run's final estimate, as the smoothed files stamp it).
  const double to_reference_s = reference_on_gps_time ? filter.gnss_time_s() - filter.state().t_s : 0.0;

  std::vector<SmoothedGap> out(windows.size());
  std::vector<double> next_t(windows.size(), -1e300);
  for (std::size_t i = 0; i < run.size(); ++i) {
    const double t = run.t_s(i);
    const int g = gap_of(t);
    if (g < 0 || t < next_t[g]) continue;
    next_t[g] = t + eval_period_s;
    const auto ref = reference.at(t + to_reference_s);
    if (!ref) continue;
    const est::SmoothedRow r = run.row(i);
    const NavDifference ds = nav_difference(sample_of(r.smoothed), *ref);
    const NavDifference df = nav_difference(sample_of(r.forward), *ref);
    SmoothedGap& s = out[g];
    ++s.samples;
    const double h = ds.pos_ned_m.head<2>().norm();
    if (h >= s.max_horizontal_m) {
      s.max_horizontal_m = h;
      s.t_max_s = t;
      s.std_horizontal_at_max_m = r.std_smoothed.head<2>().norm();
    }
    s.max_vertical_m = std::max(s.max_vertical_m, std::abs(ds.pos_ned_m.z()));
    s.forward_max_horizontal_m = std::max(s.forward_max_horizontal_m, df.pos_ned_m.head<2>().norm());
  }
  return out;
}

}  // namespace ldv::assess
