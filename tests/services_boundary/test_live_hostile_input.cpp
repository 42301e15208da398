// The live chain (fusion's engine as it runs live, through a recorded log) across a GPS week rollover and
// through one hostile but well-formed message at a time (issue 35, items 1-5): NAV keeps coming, on one
// continuous GPS time scale, finite and close to the simulator's truth.
#include <gtest/gtest.h>

#include "tests/services_boundary/hostile_log.hpp"

using namespace ldv;
using namespace ldv::testing;

namespace {

// A tactical IMU with RTK at 5 Hz and the start given from truth: the error stays at centimetres.
constexpr double kMaxHorizontalError_m = 0.3;

// NAV after the filter started: times strictly increase on the continuous scale, every seconds of week lies in
// [0, 604800), and the count covers the IMU samples after the first output (none lost).
void expect_continuous_nav(const HostileDrive& d, const ReplayedNav& r, size_t refused_imu = 0) {
  ASSERT_FALSE(r.outputs.empty());
  double last = -1.0;
  size_t backwards = 0, out_of_week = 0;
  for (const FusionOutput& o : r.outputs) {
    const double t = r.continuous_s(o, d.first_week);
    if (!(t > last)) ++backwards;
    if (!(o.gps_sow_s >= 0.0 && o.gps_sow_s < kSecondsPerWeek)) ++out_of_week;
    last = t;
  }
  EXPECT_EQ(backwards, 0u) << "NAV times must increase";
  EXPECT_EQ(out_of_week, 0u) << "a NAV seconds of week outside the week";
  const double first_t = r.continuous_s(r.outputs.front(), d.first_week) - d.shift_s;
  size_t expected = 0;
  for (const ImuIncrement& s : d.sim.imu) expected += s.t_s >= first_t - 1e-6;
  EXPECT_GE(r.outputs.size() + refused_imu, expected) << "NAV stopped";
  const double last_t = r.continuous_s(r.outputs.back(), d.first_week) - d.shift_s;
  EXPECT_NEAR(last_t, d.sim.imu.back().t_s, 0.05) << "NAV must reach the end of the drive";
}

}  // namespace

TEST(LiveHostileInput, GivenADriveAcrossAGpsWeekRollover_WhenReplayedThroughFusion_ThenNavKeepsComingIntoTheNewWeek) {
  // Given: 120 s of driving, the week ends 60 s in (week 2300 sow 604799.995 -> week 2301 sow 0).
  HostileDrive d = hostile_drive("hg1700-typical", 120.0, kSecondsPerWeek - 60.0);
  // When
  const ReplayedNav r = replay_hostile_drive(d);
  // Then
  EXPECT_EQ(r.summary.malformed, 0);
  expect_continuous_nav(d, r);
  size_t in_new_week = 0;
  for (const FusionOutput& o : r.outputs) in_new_week += o.gps_week == d.first_week + 1;
  EXPECT_GT(in_new_week, 11000u) << "60 s at 200 Hz after the rollover";
  const TruthErrors e = errors_against_truth(d, r);
  EXPECT_EQ(e.compared, r.outputs.size());
  EXPECT_LT(e.max_horizontal_m, kMaxHorizontalError_m);
}

TEST(LiveHostileInput, GivenOneImuIncrementBeyondAnyImu_ThenItIsRefusedAndNavStaysOnTruth) {
  for (const auto& [axis, value] : {std::pair{3, 1e30}, std::pair{0, 1000.0}}) {
    HostileDrive d = hostile_drive("hg1700-typical", 60.0, 345600.0);
    d.on_imu = [axis = axis, value = value](ldv_lcm::imu_sample_t& m, size_t i) {
      if (i != 6000) return;
      if (axis == 3)
        m.dvel_b_mps[0] = value;  // dvel_x = 1e30 m/s
      else
        m.dtheta_b_rad[axis] = value;  // dtheta_x = 1000 rad in 5 ms
    };
    const ReplayedNav r = replay_hostile_drive(d);
    EXPECT_EQ(r.summary.malformed, 1);
    expect_continuous_nav(d, r, 1);
    EXPECT_LT(errors_against_truth(d, r).max_horizontal_m, kMaxHorizontalError_m) << "value " << value;
  }
}

TEST(LiveHostileInput, GivenGnssVelocitiesOf1e6mps_ThenTheFixesAreRefusedAndNoNavMovesThatFast) {
  HostileDrive d = hostile_drive("hg1700-typical", 60.0, 345600.0);
  d.on_gnss = [](ldv_lcm::gnss_solution_t& m, size_t i) {
    if (i % 10 != 5) return;
    m.has_velocity = true;
    m.vel_ned_mps[0] = 1e6;
    for (int k = 0; k < 3; ++k) m.vel_var_ned_m2s2[k] = 0.01;
  };
  const ReplayedNav r = replay_hostile_drive(d);
  EXPECT_GT(r.summary.malformed, 25);
  expect_continuous_nav(d, r);
  const TruthErrors e = errors_against_truth(d, r);
  EXPECT_LT(e.max_speed_mps, 100.0);
  EXPECT_LT(e.max_horizontal_m, kMaxHorizontalError_m);
}

TEST(LiveHostileInput, GivenThreeImuStampsPastTheEndOfTheWeek_ThenTheyAreRefusedAndDoNotConfirmAJump) {
  HostileDrive d = hostile_drive("hg1700-typical", 60.0, 345600.0);
  d.on_imu = [](ldv_lcm::imu_sample_t& m, size_t i) {
    if (i >= 3000 && i < 3003) m.gps_sow_s += 1e6;  // 1345675 s: not a seconds of week
  };
  const ReplayedNav r = replay_hostile_drive(d);
  EXPECT_EQ(r.summary.malformed, 3);
  expect_continuous_nav(d, r, 3);
  EXPECT_LT(errors_against_truth(d, r).max_horizontal_m, kMaxHorizontalError_m);
}

TEST(LiveHostileInput, GivenOneFixAtAHeightOf1e300m_ThenItIsRefusedWithoutACovarianceReset) {
  HostileDrive d = hostile_drive("hg1700-typical", 60.0, 345600.0);
  d.on_gnss = [](ldv_lcm::gnss_solution_t& m, size_t i) {
    if (i == 100) m.height_m = 1e300;
  };
  const ReplayedNav r = replay_hostile_drive(d);
  EXPECT_EQ(r.summary.malformed, 1);
  expect_continuous_nav(d, r);
  EXPECT_LT(errors_against_truth(d, r).max_horizontal_m, kMaxHorizontalError_m);
  size_t resets = 0;
  for (const FusionOutput& o : r.outputs) resets += (o.status & est::kStatusCovarianceReset) != 0;
  EXPECT_EQ(resets, 0u);
}

TEST(LiveHostileInput, GivenEveryFixClaimingAVarianceOf1e300m2_ThenNavStaysAsGoodAsWithTheTrueStd) {
  // A receiver claiming 1e-150 m is claiming what no receiver can: it is held to the best a receiver can
  // deliver (1 mm), not trusted to the last bit (the covariance then loses positive-definiteness).
  HostileDrive d = hostile_drive("hg1700-typical", 60.0, 345600.0);
  d.on_gnss = [](ldv_lcm::gnss_solution_t& m, size_t) {
    for (int k = 0; k < 9; ++k) m.pos_cov_ned_m2[k] = k % 4 == 0 ? 1e-300 : 0.0;
  };
  const ReplayedNav r = replay_hostile_drive(d);
  expect_continuous_nav(d, r);
  EXPECT_LT(errors_against_truth(d, r).max_horizontal_m, kMaxHorizontalError_m);
  double sum_sq_ve = 0.0;
  size_t n = 0;
  std::map<long, const sim::TruthSample*> truth;
  for (const auto& s : d.sim.truth) truth[std::lround(s.t_s * 1e3)] = &s;
  for (const FusionOutput& o : r.outputs) {
    const auto it = truth.find(std::lround((r.continuous_s(o, d.first_week) - d.shift_s) * 1e3));
    if (it == truth.end()) continue;
    const double dve = o.state.v_n_mps[1] - it->second->vel_n_mps[1];
    sum_sq_ve += dve * dve;
    ++n;
  }
  ASSERT_GT(n, 0u);
  EXPECT_LT(std::sqrt(sum_sq_ve / n), 0.05) << "east velocity RMS against truth";
  size_t resets = 0;
  for (const FusionOutput& o : r.outputs) resets += (o.status & est::kStatusCovarianceReset) != 0;
  EXPECT_EQ(resets, 0u);
}

// The first IMU message stamped a week ahead (week 2301 for 2300) took the stream's clock with it: every real
// sample after it looked a week old and was refused, NAV never came. The real time line is followed after a
// second and navigation starts on it.
TEST(LiveHostileInput, GivenTheFirstImuMessageStampedAWeekAhead_ThenNavComesOnTheRealTimeLine) {
  HostileDrive d = hostile_drive("hg1700-typical", 60.0, 345600.0);
  d.on_imu = [](ldv_lcm::imu_sample_t& m, size_t i) {
    if (i == 0) m.gps_week += 1;
  };
  const ReplayedNav r = replay_hostile_drive(d);
  ASSERT_FALSE(r.outputs.empty()) << "NAV never came";
  EXPECT_EQ(r.outputs.back().gps_week, d.first_week);
  const double last_t = r.continuous_s(r.outputs.back(), d.first_week) - d.shift_s;
  EXPECT_NEAR(last_t, d.sim.imu.back().t_s, 0.05) << "NAV must reach the end of the drive";
  EXPECT_GT(r.outputs.size(), d.sim.imu.size() - 2 * 200u) << "at most the confirmation second and the restart lost";
  EXPECT_LT(errors_against_truth(d, r).max_horizontal_m, 1.0);
}
