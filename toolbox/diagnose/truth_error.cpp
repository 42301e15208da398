#include "toolbox/diagnose/truth_error.hpp"

#include <algorithm>
#include <cmath>

#include "common/geo/earth_model.hpp"

namespace ldv::diag {

TruthError truth_error(const FilterRun& run, const std::vector<Segment>& labels, const std::vector<NavRecord>& truth,
                       double skip_s) {
  TruthError te;
  if (truth.empty() || run.epochs.empty()) return te;
  const double t0 = run.epochs.front().t_s + skip_s;
  double s3 = 0.0, sh = 0.0, sv = 0.0, syaw = 0.0;
  std::array<double, kSegmentCount> seg_sum{};
  std::array<int, kSegmentCount> seg_n{};
  int n = 0;
  for (size_t i = 0; i < run.epochs.size(); ++i) {
    const EpochSample& e = run.epochs[i];
    auto it = std::lower_bound(truth.begin(), truth.end(), e.t_s - 1e-4,
                               [](const NavRecord& r, double t) { return r.sow_s < t; });
    if (it == truth.end() || std::abs(it->sow_s - e.t_s) > 2e-3) continue;
    const Vec3 d = earth::ned_between(it->pos, e.pos);
    te.t_s.push_back(e.t_s);
    te.pos_err_ned_m.push_back(d);
    if (e.t_s < t0) continue;
    ++n;
    s3 += d.squaredNorm();
    sh += d.head<2>().squaredNorm();
    sv += d.z() * d.z();
    te.max_horizontal_m = std::max(te.max_horizontal_m, d.head<2>().norm());
    double dyaw = std::remainder(e.rpy_rad.z() - it->rpy_rad.z(), 2.0 * kPi);
    syaw += dyaw * dyaw;
    const int s = static_cast<int>(labels[i]);
    seg_sum[s] += d.squaredNorm();
    ++seg_n[s];
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
