// Given/when/then for the GNSS jump gate: smooth motion passes, a jump of tens of metres is
// rejected, a jump that persists is followed, a long gap restarts.
#include <gtest/gtest.h>

#include "common/geo/earth_model.hpp"
#include "common/formats/gnss_jump_gate.hpp"

using namespace ldv;
using namespace ldv::gnss;

namespace {
// A solution `north_m` north of 45 N 7 E at time t.
GnssSolution at(double t_s, double north_m, bool with_velocity = false, double vn_mps = 0) {
  GnssSolution s;
  s.time = GpsTime{2300, 1000.0 + t_s};
  s.fix.pos = Geodetic{(45.0 + north_m / 111132.0) * M_PI / 180.0, 7.0 * M_PI / 180.0, 300.0};
  s.fix.has_velocity = with_velocity;
  s.fix.vel_n_mps = Vec3(vn_mps, 0, 0);
  return s;
}
}  // namespace

TEST(JumpGate, GivenAVehicleAt5mps_ThenEveryEpochIsAccepted) {
  JumpGate gate;
  EXPECT_EQ(gate.check(at(0, 0)), JumpVerdict::kRestarted);
  for (int k = 1; k < 20; ++k) EXPECT_EQ(gate.check(at(k * 0.2, k * 1.0)), JumpVerdict::kAccepted) << k;
  EXPECT_EQ(gate.counters().jumps_rejected, 0u);
}

TEST(JumpGate, GivenA40mJump_ThenRejectedAndTheNextGoodEpochAccepted) {
  JumpGate gate;
  gate.check(at(0, 0));
  gate.check(at(1, 5));
  EXPECT_EQ(gate.check(at(2, 10 + 40)), JumpVerdict::kJumpRejected);
  EXPECT_NEAR(gate.last_deviation_m(), 40.0, 0.1);
  EXPECT_EQ(gate.check(at(3, 15)), JumpVerdict::kAccepted);  // predicted from the last two accepted
  EXPECT_EQ(gate.counters().jumps_rejected, 1u);
}

TEST(JumpGate, GivenTheSolutionsOwnVelocity_ThenThePredictionUsesIt) {
  JumpGate gate;
  gate.check(at(0, 0, true, 20.0));
  // 20 m/s north for 1 s: 20 m is where it should be, 0 m is 20 m off but under 30 m.
  EXPECT_EQ(gate.check(at(1, 20, true, 20.0)), JumpVerdict::kAccepted);
  EXPECT_EQ(gate.check(at(2, 20 + 20 - 35, true, 20.0)), JumpVerdict::kJumpRejected);
}

TEST(JumpGate, GivenAJumpThatPersists_ThenTheGateFollowsItAfterFiveEpochs) {
  JumpGate gate;
  gate.check(at(0, 0));
  gate.check(at(1, 0));
  for (int k = 2; k < 6; ++k) EXPECT_EQ(gate.check(at(k, 100)), JumpVerdict::kJumpRejected);
  EXPECT_EQ(gate.check(at(6, 100)), JumpVerdict::kRestarted);
  EXPECT_EQ(gate.check(at(7, 100)), JumpVerdict::kAccepted);
}

TEST(JumpGate, GivenALongGapOrTimeGoingBack_ThenRestartOrReject) {
  JumpGate gate;
  gate.check(at(0, 0));
  gate.check(at(1, 0));
  EXPECT_EQ(gate.check(at(1, 0)), JumpVerdict::kTimeRejected);  // duplicate epoch
  EXPECT_EQ(gate.check(at(20, 500)), JumpVerdict::kRestarted);  // 19 s gap: nothing to predict from
}
