// The score test is only as good as the sensitivities it carries through the filter. Given a short
// drive, when the data are changed by a small known amount of one effect, then the filter's
// innovations change by the predicted s * delta_e (same filter, same gains: first order).
#include <gtest/gtest.h>

#include "tests/diagnose/sim_case.hpp"

namespace ldv::diag {
namespace {

struct Perturbed {
  std::vector<SensitivityRecord> base, changed;
  int column = 0;
};

// Runs the screening run twice: on the inputs, and on the inputs changed by `change`.
template <typename Change>
Perturbed run_pair(const std::string& model, const std::string& effect, Change change) {
  testing::SimCase c;
  c.duration_s = 240.0;
  const sim::SimResult r = testing::simulate(c);
  DiagnoseInputs in = testing::inputs(r);
  est::FilterOptions o = est::options_from_kfgins(r.kfgins);
  o.model = model;
  const CandidateSet set = make_candidates(o, est::resolve_model(o.model, o.add, o.drop));
  Perturbed p;
  p.base = run_filter(in, o, &set).records;
  change(in, o);
  p.changed = run_filter(in, o, &set).records;
  for (const Candidate& cand : set.candidates)
    if (cand.name == effect) p.column = cand.column;
  return p;
}

// Relative misfit |d_nu - s de| / |d_nu| over the measurements of both runs (matched by kind and time:
// a shifted time tag may move a fix across the initial epoch).
double misfit(const Perturbed& p, const Eigen::VectorXd& de) {
  double num = 0.0, den = 0.0;
  size_t j = 0, matched = 0;
  for (size_t i = 0; i < p.base.size(); ++i) {
    while (j < p.changed.size() && p.changed[j].t_s < p.base[i].t_s - 0.05) ++j;
    if (j >= p.changed.size()) break;
    size_t k = j;
    while (k < p.changed.size() && p.changed[k].sensor != p.base[i].sensor && p.changed[k].t_s < p.base[i].t_s + 0.05)
      ++k;
    if (k >= p.changed.size() || std::abs(p.changed[k].t_s - p.base[i].t_s) > 0.05 ||
        p.changed[k].sensor != p.base[i].sensor)
      continue;
    ++matched;
    const Vec3 d_nu = p.changed[k].innovation - p.base[i].innovation;
    const Vec3 pred = p.base[i].s.middleCols(p.column, de.size()) * de;
    num += (d_nu - pred).squaredNorm();
    den += d_nu.squaredNorm();
  }
  EXPECT_GT(matched, p.base.size() * 9 / 10);
  return std::sqrt(num / den);
}

}  // namespace

TEST(DiagnoseSensitivity, LeverArmAssumedValuePredictsTheInnovationChange) {
  const Vec3 dl(0.02, -0.01, 0.015);  // assumed lever arm moved: e = assumed - true grows by dl
  const Perturbed p = run_pair("kfgins21", "lever_arm", [&](DiagnoseInputs&, est::FilterOptions& o) { o.lever_arm.init += dl; });
  EXPECT_LT(misfit(p, dl), 0.1);
}

TEST(DiagnoseSensitivity, TimeOffsetInTheDataPredictsTheInnovationChange) {
  const double dt = 0.002;  // GNSS labels later by dt: the true offset grows, e falls by dt
  const Perturbed p = run_pair("kfgins21", "time_offset", [&](DiagnoseInputs& in, est::FilterOptions&) {
    for (GnssFix& f : in.gnss) f.t_s += dt;
  });
  EXPECT_LT(misfit(p, Eigen::VectorXd::Constant(1, -dt)), 0.15);
}

TEST(DiagnoseSensitivity, GyroScaleInTheDataPredictsTheInnovationChange) {
  const Vec3 ds(2e-4, -3e-4, 5e-4);  // raw rates scaled by (1 + ds): true scale grows, e falls
  const Perturbed p = run_pair("ins15", "gyro_scale", [&](DiagnoseInputs& in, est::FilterOptions&) {
    for (ImuIncrement& m : in.imu) m.dtheta_b_rad += ds.cwiseProduct(m.dtheta_b_rad);
  });
  EXPECT_LT(misfit(p, -ds), 0.15);
}

TEST(DiagnoseSensitivity, AccelMisalignmentInTheDataPredictsTheInnovationChange) {
  const Vec3 dm(2e-4, -1e-4, 3e-4);  // f_meas += N(dm) f: true misalignment grows, e falls
  const Perturbed p = run_pair("kfgins21", "accel_misalignment", [&](DiagnoseInputs& in, est::FilterOptions&) {
    for (ImuIncrement& m : in.imu) m.dvel_b_mps += est::misalignment_matrix(dm) * m.dvel_b_mps;
  });
  EXPECT_LT(misfit(p, -dm), 0.15);
}

}  // namespace ldv::diag
