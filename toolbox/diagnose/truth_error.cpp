#include "toolbox/diagnose/truth_error.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "common/geo/earth_model.hpp"
#include "common/math/rotation.hpp"
#include "toolbox/assess/nav_series.hpp"

namespace ldv::diag {

TruthError truth_error(const FilterRun& run, const std::vector<Segment>& labels, const std::vector<NavRecord>& truth,
                       double skip_s) {
  TruthError te;
  te.given = !truth.empty();
  if (truth.empty() || run.epochs.empty()) return te;
  const double t0 = run.epochs.front().t_s + skip_s;
  double s3 = 0.0, sh = 0.0, sv = 0.0, syaw = 0.0;
  std::array<double, kSegmentCount> seg_sum{};
  std::array<int, kSegmentCount> seg_n{};
  int n = 0;
  // Interpolated, not matched to a truth row: epochs whose IMU stamps were shifted (a latency taken out) or
  // that carry a time offset fall between the truth's rows.
  const assess::NavSeries truth_series = assess::NavSeries::from_records(truth);
  for (size_t i = 0; i < run.epochs.size(); ++i) {
    const EpochSample& e = run.epochs[i];
    if (e.t_s >= t0) ++te.run_epochs;
    const std::optional<assess::NavSample> tr = truth_series.at(e.t_s);
    if (!tr) continue;
    const Vec3 d = earth::ned_between(tr->pos, e.pos);
    te.t_s.push_back(e.t_s);
    te.pos_err_ned_m.push_back(d);
    if (e.t_s < t0) continue;
    ++n;
    ++te.compared_epochs;
    s3 += d.squaredNorm();
    sh += d.head<2>().squaredNorm();
    sv += d.z() * d.z();
    te.max_horizontal_m = std::max(te.max_horizontal_m, d.head<2>().norm());
    const double dyaw = std::remainder(e.rpy_rad.z() - euler_from_C_b_n(tr->q_b_n.toRotationMatrix()).z(), 2.0 * kPi);
    syaw += dyaw * dyaw;
    const int s = static_cast<int>(labels[i]);
    seg_sum[s] += d.squaredNorm();
    ++seg_n[s];
  }
  // No result on no data, and no silent part (issue 46): say what the truth covered.
  if (te.compared_epochs < te.run_epochs) {
    char b[300];
    std::snprintf(b, sizeof b,
                  "the truth (%.3f to %.3f s) covers %d of the run's %d epochs from %.3f to %.3f s "
                  "(the first %.0f s left out)",
                  truth_series.t_begin_s(), truth_series.t_end_s(), te.compared_epochs, te.run_epochs, t0,
                  run.epochs.back().t_s, skip_s);
    te.coverage_note = b;
  }
  if (n == 0) return te;
  te.available = true;
  te.rms_pos_3d_m = std::sqrt(s3 / n);
  te.rms_horizontal_m = std::sqrt(sh / n);
  te.rms_vertical_m = std::sqrt(sv / n);
  te.rms_yaw_deg = std::sqrt(syaw / n) * kRadToDeg;
  for (int s = 0; s < kSegmentCount; ++s) te.rms_pos_3d_by_segment_m[s] = seg_n[s] ? std::sqrt(seg_sum[s] / seg_n[s]) : 0.0;
  return te;
}

}  // namespace ldv::diag
