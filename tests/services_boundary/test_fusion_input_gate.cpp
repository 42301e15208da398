// fusion's input gate: one IMU message stamped far ahead must not freeze the stream; a real jump is followed;
// samples flagged as device errors are not navigation data.
#include <gtest/gtest.h>

#include "common/bus/message_conversions.hpp"
#include "services/fusion/fusion_input_gate.hpp"

using namespace ldv;

namespace {
constexpr int kWeek = 2300;
ldv_lcm::imu_sample_t imu_at(double sow_s, int32_t status = 0) {
  ldv_lcm::imu_sample_t m{};
  m.gps_week = kWeek;
  m.gps_sow_s = sow_s;
  m.dt_s = 0.01;
  m.dvel_b_mps[2] = -0.0981;
  m.status = status;
  return m;
}
}  // namespace

TEST(FusionInputGate, GivenOneImuMessageStamped1000sAhead_ThenItIsRefusedAndEveryLaterSampleAccepted) {
  FusionInputGate gate({});
  int accepted = 0;
  for (int k = 0; k < 100; ++k) accepted += gate.check(imu_at(1000.0 + 0.01 * k)) == InputVerdict::kAccepted;
  EXPECT_EQ(gate.check(imu_at(2000.0)), InputVerdict::kTooFarAhead);
  for (int k = 100; k < 200; ++k) accepted += gate.check(imu_at(1000.0 + 0.01 * k)) == InputVerdict::kAccepted;
  EXPECT_EQ(accepted, 200);
  EXPECT_EQ(gate.counters().too_far_ahead, 1);
  EXPECT_EQ(gate.counters().malformed(), 1);
}

TEST(FusionInputGate, GivenARealForwardJump_ThenTheGateFollowsOnceTheNewTimeLineHeldForASecond) {
  FusionInputGate gate({});
  for (int k = 0; k < 10; ++k) ASSERT_EQ(gate.check(imu_at(1000.0 + 0.01 * k)), InputVerdict::kAccepted);
  // The IMU resumes 30 s later (imu_acq restarted): held back until its new time line has held for 1 s.
  int held = 0;
  for (int k = 0; k < 100; ++k) held += gate.check(imu_at(1030.00 + 0.01 * k)) == InputVerdict::kTooFarAhead;
  EXPECT_EQ(held, 100);
  EXPECT_EQ(gate.check(imu_at(1031.00)), InputVerdict::kAccepted);
  EXPECT_EQ(gate.check(imu_at(1031.01)), InputVerdict::kAccepted);
  // Stamps at or before the last accepted one are refused (a stream only goes forward).
  EXPECT_EQ(gate.check(imu_at(1031.01)), InputVerdict::kNotAfterLast);
  EXPECT_EQ(gate.check(imu_at(1000.5)), InputVerdict::kNotAfterLast);
}

// Issue 35, item 4 (and what the fuzzer's streams found beside it): a few corrupted stamps that agree with each
// other (sow + 1000 s, + 1000.01, + 1000.02) are not a new time line; the stream goes on at its own time.
TEST(FusionInputGate, GivenThreeAgreeingCorruptedStamps_ThenTheyAreRefusedAndTheStreamGoesOn) {
  FusionInputGate gate({});
  for (int k = 0; k < 10; ++k) ASSERT_EQ(gate.check(imu_at(1000.0 + 0.01 * k)), InputVerdict::kAccepted);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(gate.check(imu_at(2000.10 + 0.01 * k)), InputVerdict::kTooFarAhead);
  for (int k = 13; k < 200; ++k) ASSERT_EQ(gate.check(imu_at(1000.0 + 0.01 * k)), InputVerdict::kAccepted) << k;
}

TEST(FusionInputGate, GivenDeviceErrorSamples_ThenTheyAreRefusedAndCounted) {
  FusionInputGate gate({});
  EXPECT_EQ(gate.check(imu_at(10.00)), InputVerdict::kAccepted);
  for (int k = 1; k <= 200; ++k)  // 2 s of saturated samples at 100 Hz
    EXPECT_EQ(gate.check(imu_at(10.0 + 0.01 * k, kImuStatusDeviceError)), InputVerdict::kDeviceError);
  EXPECT_EQ(gate.counters().device_error, 200);
  EXPECT_EQ(gate.check(imu_at(12.01)), InputVerdict::kAccepted);  // the gap is bridged by the filter
}

TEST(FusionInputGate, GivenHostClockOrNaNSamples_ThenTheyAreRefusedForTheirReason) {
  FusionInputGate gate({});
  EXPECT_EQ(gate.check(imu_at(10.0, kImuStatusTimeExtrapolated)), InputVerdict::kNotGpsTime);
  auto nan = imu_at(10.0);
  nan.dtheta_b_rad[1] = std::nan("");
  EXPECT_EQ(gate.check(nan), InputVerdict::kNotFinite);
  EXPECT_EQ(gate.counters().malformed(), 1);  // host-clock samples are expected, not bad input
}

TEST(FusionInputGate, GivenAGnssFixFarAheadOfTheImuClock_ThenItIsRefused) {
  FusionInputGate gate({});
  ASSERT_EQ(gate.check(imu_at(100.0)), InputVerdict::kAccepted);
  ldv_lcm::gnss_solution_t g = message_from_gnss(GnssFix{}, kWeek, 0);
  g.gps_week = kWeek;
  g.gps_sow_s = 99.8;
  EXPECT_EQ(gate.check(g), InputVerdict::kAccepted);
  g.gps_sow_s = 1100.0;
  EXPECT_EQ(gate.check(g), InputVerdict::kTooFarAhead);
}

// A stream that went back in time as a whole (a receiver corrected its week; the first sample was stamped a week
// ahead) was refused for ever: fusion froze. It is followed once the time line behind has held for a second, and
// counted for the engine to restart on; a single old message in between keeps being refused.
TEST(FusionInputGate, GivenTheWholeStreamGoingBackInTime_ThenTheGateFollowsAfterASecondAndCountsIt) {
  FusionInputGate gate({});
  for (int k = 0; k < 10; ++k) ASSERT_EQ(gate.check(imu_at(5000.0 + 0.01 * k)), InputVerdict::kAccepted);
  EXPECT_EQ(gate.check(imu_at(1000.0)), InputVerdict::kNotAfterLast);  // one old message
  EXPECT_EQ(gate.check(imu_at(5000.10)), InputVerdict::kAccepted);
  int held = 0;
  for (int k = 0; k < 100; ++k) held += gate.check(imu_at(1000.0 + 0.01 * k)) == InputVerdict::kNotAfterLast;
  EXPECT_EQ(held, 100);
  EXPECT_EQ(gate.imu_jumps_back(), 0);
  EXPECT_EQ(gate.check(imu_at(1001.00)), InputVerdict::kAccepted);
  EXPECT_EQ(gate.imu_jumps_back(), 1);
  EXPECT_EQ(gate.check(imu_at(1001.01)), InputVerdict::kAccepted);
}

// Issue 35, item 29 on the bus: two IMU stamps 3 ns or 10 ns apart gave NAV epochs at one printed time. The second
// is the same sample again: refused, and the stream goes on.
TEST(FusionInputGate, GivenTwoImuStampsNanosecondsApart_ThenTheSecondIsRefused) {
  for (const double apart_s : {3e-9, 1e-8}) {
    FusionInputGate gate({});
    ASSERT_EQ(gate.check(imu_at(1000.0)), InputVerdict::kAccepted);
    EXPECT_EQ(gate.check(imu_at(1000.0 + apart_s)), InputVerdict::kNotAfterLast);
    EXPECT_EQ(gate.check(imu_at(1000.01)), InputVerdict::kAccepted);
  }
}
