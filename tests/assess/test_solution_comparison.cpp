// `ldv compare` (paper Tables 10-11): identical solutions give zeros, a known offset gives that offset,
// B is interpolated at A's epochs, the settling time is honoured; the .nav round trip.
#include <gtest/gtest.h>

#include <filesystem>

#include "common/formats/kfgins_files.hpp"
#include "common/geo/earth_model.hpp"
#include "toolbox/assess/solution_comparison.hpp"

using namespace ldv;
using namespace ldv::assess;

namespace {

// A vehicle driving north-east at 10 m/s, turning slowly; 10 Hz.
NavSeries moving(double t0, double dt, int n, const Vec3& offset_ned_m = Vec3::Zero(), const Vec3& dv = Vec3::Zero(),
                 const Vec3& drpy_rad = Vec3::Zero()) {
  std::vector<NavSample> v;
  const Geodetic origin{0.6, -1.9, 120.0};
  for (int i = 0; i < n; ++i) {
    const double t = t0 + i * dt;
    const Vec3 vel(7.0, 7.0, 0.0);
    NavSample s;
    s.t_s = t;
    s.pos = earth::offset_ned(origin, vel * (t - 1000.0) + offset_ned_m);
    s.vel_n_mps = vel + dv;
    s.q_b_n = quat_from_euler(Vec3(0.01, -0.02, 0.7 + 0.001 * (t - 1000.0)) + drpy_rad);
    v.push_back(s);
  }
  return NavSeries(std::move(v));
}

}  // namespace

TEST(SolutionComparison, IdenticalSolutionsGiveZeros) {
  const NavSeries a = moving(1000.0, 0.1, 600);
  const ComparisonResult r = compare_solutions(a, a, {});
  EXPECT_EQ(r.epochs, 600);
  for (const ComponentStats& s : r.stats) {
    EXPECT_NEAR(s.mean, 0.0, 1e-9);
    EXPECT_NEAR(s.rms, 0.0, 1e-9);
    EXPECT_NEAR(s.std, 0.0, 1e-9);
  }
}

TEST(SolutionComparison, KnownOffsetIsRecoveredWithInterpolation) {
  // B sampled at other epochs (every 0.25 s, shifted) than A: linear motion interpolates exactly.
  const NavSeries b = moving(999.0, 0.25, 300);
  const NavSeries a = moving(1000.05, 0.1, 500, Vec3(1.0, -2.0, 0.5), Vec3(0.1, -0.2, 0.05), Vec3(0.5, -0.3, 1.0) * kDegToRad);
  const ComparisonResult r = compare_solutions(a, b, {10.0, 1.5});
  EXPECT_EQ(r.epochs, 400);  // the first 10 s are settling
  const double expect[kComponents] = {-2.0, 1.0, 0.5, -0.2, 0.1, 0.05, 0.5, -0.3, 1.0};  // E N D, vE vN vD, r p y
  for (int i = 0; i < kComponents; ++i) {
    EXPECT_NEAR(r.stats[i].mean, expect[i], 2e-4) << kComponentNames[i];
    EXPECT_NEAR(r.stats[i].rms, std::abs(expect[i]), 2e-4) << kComponentNames[i];
    EXPECT_NEAR(r.stats[i].std, 0.0, 2e-4) << kComponentNames[i];
  }
}

TEST(SolutionComparison, MeanStdAndRmsOfAnAlternatingOffset) {
  // North offset alternating +1/-1 m around a 0.5 m mean: mean 0.5, std 1, RMS sqrt(1.25).
  std::vector<NavSample> a = moving(1000.0, 0.1, 400).samples();
  for (size_t i = 0; i < a.size(); ++i)
    a[i].pos = earth::offset_ned(a[i].pos, Vec3(0.5 + (i % 2 ? 1.0 : -1.0), 0, 0));
  const ComparisonResult r = compare_solutions(NavSeries(a), moving(1000.0, 0.1, 400), {});
  EXPECT_NEAR(r.stats[1].mean, 0.5, 1e-4);
  EXPECT_NEAR(r.stats[1].std, 1.0, 1e-4);
  EXPECT_NEAR(r.stats[1].rms, std::sqrt(1.25), 1e-4);
}

TEST(SolutionComparison, NavFileRoundTripAndNoSharedEpochs) {
  const std::string path = (std::filesystem::temp_directory_path() / "ldv_compare_test.nav").string();
  {
    NavWriter w(path);
    const auto track = moving(1000.0, 0.1, 100);  // named: samples() refers into it
    for (const NavSample& s : track.samples()) {
      NavRecord r;
      r.week = 2300;
      r.sow_s = s.t_s;
      r.pos = s.pos;
      r.vel_n_mps = s.vel_n_mps;
      r.rpy_rad = euler_from_C_b_n(s.q_b_n.toRotationMatrix());
      w.write(r);
    }
  }
  const NavSeries f = NavSeries::from_records(read_nav(path));
  const ComparisonResult r = compare_solutions(f, moving(1000.0, 0.1, 100), {});
  EXPECT_LT(r.stats[0].rms, 0.01);  // the .nav keeps ~1e-9 deg
  EXPECT_LT(r.stats[8].rms, 1e-6);
  EXPECT_THROW(compare_solutions(f, moving(5000.0, 0.1, 10), {}), std::invalid_argument);
  std::filesystem::remove(path);
}
