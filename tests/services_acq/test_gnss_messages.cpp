// Decoded solutions and labels -> gnss_solution_t / pps_event_t, and the label back as imu_acq reads it.
#include <gtest/gtest.h>

#include "common/bus/gnss_messages.hpp"

using namespace ldv;
using namespace ldv::gnss;

TEST(GnssMessages, GivenASolution_ThenEveryFieldInItsUnit) {
  GnssSolution s;
  s.time = GpsTime{2320, 116418.2};
  s.fix.pos = Geodetic{35.0 * M_PI / 180, 137.0 * M_PI / 180, 104.86};
  s.pos_cov_ned_m2 << 4e-4, 1e-5, 0, 1e-5, 9e-4, 0, 0, 0, 2.5e-3;
  s.fix.has_velocity = true;
  s.fix.vel_n_mps = Vec3(1, -2, 0.5);
  s.fix.vel_std_n_mps = Vec3(0.1, 0.2, 0.3);
  s.fix.quality = GnssQuality::kFloat;
  s.fix.num_sats = 17;
  s.fix.age_s = 1.5;
  s.fix.ratio = 2.5;
  const auto m = to_message(s, 42, 1.7e9);
  EXPECT_EQ(m.seq, 42);
  EXPECT_EQ(m.gps_week, 2320);
  EXPECT_DOUBLE_EQ(m.gps_sow_s, 116418.2);
  EXPECT_DOUBLE_EQ(m.host_time_s, 1.7e9);
  EXPECT_NEAR(m.lat_deg, 35.0, 1e-12);
  EXPECT_NEAR(m.lon_deg, 137.0, 1e-12);
  EXPECT_DOUBLE_EQ(m.height_m, 104.86);
  EXPECT_DOUBLE_EQ(m.pos_cov_ned_m2[1], 1e-5);
  EXPECT_DOUBLE_EQ(m.pos_cov_ned_m2[8], 2.5e-3);
  EXPECT_TRUE(m.has_velocity);
  EXPECT_DOUBLE_EQ(m.vel_ned_mps[1], -2);
  EXPECT_NEAR(m.vel_var_ned_m2s2[2], 0.09, 1e-12);
  EXPECT_EQ(m.fix_quality, 2);
  EXPECT_EQ(m.num_sats, 17);
  EXPECT_FLOAT_EQ(m.age_s, 1.5f);
  EXPECT_FLOAT_EQ(m.ratio, 2.5f);
}

TEST(GnssMessages, GivenLabels_ThenGpsSecondNoCounterAndWhichPulseInTheFlags) {
  PpsTimeLabel next;
  next.pulse_time = GpsTime{2320, 116419.0};
  next.refers = PpsTimeLabel::Refers::kNextPulse;
  const auto m = to_message(next, 3, 1.0, 2320LL * 604800 + 116417);  // 116418 missing
  EXPECT_EQ(m.counter_raw, -1);
  EXPECT_EQ(m.gps_week, 2320);
  EXPECT_DOUBLE_EQ(m.gps_sow_s, 116419.0);
  EXPECT_TRUE(m.flags & kPpsFlagMissingPrevious);
  EXPECT_TRUE(m.flags & kPpsFlagLabelsNextPulse);
  EXPECT_EQ(label_from_message(m).refers, PpsTimeLabel::Refers::kNextPulse);

  PpsTimeLabel last;
  last.pulse_time = GpsTime{2320, 604799.0};
  const auto n = to_message(last, 4, 1.0, 2320LL * 604800 + 604798);
  EXPECT_EQ(n.flags, 0);
  EXPECT_EQ(label_from_message(n).refers, PpsTimeLabel::Refers::kLastPulse);
  EXPECT_EQ(label_total_second(label_from_message(n)), 2320LL * 604800 + 604799);
}
