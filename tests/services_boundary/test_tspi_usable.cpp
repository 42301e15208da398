// tspi_pub: a NAV with a non-finite number is never forwarded as TSPI, let alone marked aided.
#include <gtest/gtest.h>

#include <cmath>

#include "services/tspi_pub/tspi_from_nav.hpp"

using namespace ldv;

namespace {
ldv_lcm::nav_state_t aided_nav(double sow_s) {
  ldv_lcm::nav_state_t n{};
  n.gps_week = 2300;
  n.gps_sow_s = sow_s;
  n.lat_deg = 35.1;
  n.lon_deg = 136.9;
  n.height_m = 100.0;
  n.mode = 2;  // navigating aided
  for (int i = 0; i < 3; ++i) n.pos_std_ned_m[i] = 0.02f, n.vel_std_ned_mps[i] = 0.01f, n.att_std_deg[i] = 0.1f;
  return n;
}
}  // namespace

TEST(TspiUsable, GivenAFiniteAidedNav_ThenTspiIsAidedAtRtkLevel) {
  TspiDecimator d(10.0);
  const auto t = d.on_nav(aided_nav(100.0));
  ASSERT_TRUE(t);
  EXPECT_EQ(t->quality, 3);
}

TEST(TspiUsable, GivenANanAnywhereInAnAidedNav_ThenNoTspiAndQualityInvalid) {
  const auto nan = std::nanf("");
  std::vector<ldv_lcm::nav_state_t> bad(6, aided_nav(100.0));
  bad[0].vel_ned_mps[1] = nan;
  bad[1].rpy_deg[2] = nan;
  bad[2].pos_std_ned_m[0] = nan;
  bad[3].att_std_deg[1] = -1.0f;
  bad[4].height_m = INFINITY;
  bad[5].gps_sow_s = nan;
  for (std::size_t i = 0; i < bad.size(); ++i) {
    TspiDecimator d(10.0);
    EXPECT_FALSE(TspiDecimator::is_usable(bad[i])) << i;
    EXPECT_EQ(TspiDecimator::quality_of(bad[i]), 0) << i;
    EXPECT_FALSE(d.on_nav(bad[i])) << i;
  }
}

// Issue 35 (items 2, 3): TSPI never goes back for one old or absurd NAV, and never carries a speed or height no
// vehicle has; but when NAV as a whole went back (fusion restarted on an input time line that went back), TSPI
// follows once that line has held for a second instead of falling silent until the clock catches up.
TEST(TspiUsable, GivenNavGoingBackOnceOrForGood_ThenTspiRefusesTheOneAndFollowsTheOther) {
  TspiDecimator d(10.0);
  int sent = 0;
  for (int k = 0; k < 100; ++k) sent += d.on_nav(aided_nav(5000.0 + 0.01 * k)).has_value();
  EXPECT_EQ(sent, 10);
  EXPECT_FALSE(d.on_nav(aided_nav(4000.0)));  // one old NAV
  ldv_lcm::nav_state_t fast = aided_nav(5001.0);
  fast.vel_ned_mps[0] = 1e6;
  EXPECT_FALSE(d.on_nav(fast));
  ldv_lcm::nav_state_t high = aided_nav(5001.0);
  high.height_m = -8.6e22;
  EXPECT_FALSE(d.on_nav(high));
  int during = 0, after = 0;
  for (int k = 0; k < 100; ++k) during += d.on_nav(aided_nav(1000.0 + 0.01 * k)).has_value();
  for (int k = 100; k < 200; ++k) after += d.on_nav(aided_nav(1000.0 + 0.01 * k)).has_value();
  EXPECT_EQ(during, 0) << "held back for the first second";
  EXPECT_EQ(after, 10) << "then 10 Hz on the new time line";
}
