// The Bus wrapper on LCM's in-process memq:// provider: typed round trip, malformed messages counted.
#include <gtest/gtest.h>

#include <ldv_lcm/gnss_solution_t.hpp>
#include <ldv_lcm/imu_sample_t.hpp>

#include "common/bus/bus.hpp"

using namespace ldv;

TEST(Bus, TypedRoundTripAndSequenceGaps) {
  Bus bus("memq://");
  std::vector<int64_t> seqs;
  SequenceTracker tracker;
  bus.subscribe<ldv_lcm::imu_sample_t>("IMU", [&](const ldv_lcm::imu_sample_t& m, const std::string&) {
    seqs.push_back(m.seq);
    tracker.observe(m.seq);
  });
  ldv_lcm::imu_sample_t m{};
  for (int64_t s : {0, 1, 2, 5, 6}) {
    m.seq = s;
    m.dtheta_b_rad[2] = 0.001 * s;
    ASSERT_TRUE(bus.publish("IMU", m));
  }
  while (bus.handle(0) > 0) {
  }
  EXPECT_EQ(seqs, (std::vector<int64_t>{0, 1, 2, 5, 6}));
  EXPECT_EQ(tracker.lost(), 2);
}

TEST(Bus, WrongFingerprintIsCountedNotDelivered) {
  Bus bus("memq://");
  int delivered = 0;
  bus.subscribe<ldv_lcm::imu_sample_t>("IMU", [&](const ldv_lcm::imu_sample_t&, const std::string&) { ++delivered; });
  ldv_lcm::gnss_solution_t other{};
  ASSERT_TRUE(bus.publish("IMU", other));  // a different type on our channel
  while (bus.handle(0) > 0) {
  }
  EXPECT_EQ(delivered, 0);
  EXPECT_EQ(bus.malformed(), 1);
}

// LCM 1.3.1 returns a subscription without a handler for a channel expression regcomp refuses, and setting its
// queue dereferenced NULL: `ldv_logger -c '*'` died with SIGSEGV. The bus refuses such an expression by name.
TEST(Bus, GivenAChannelExpressionRegcompRefuses_WhenSubscribing_ThenAnErrorNamesItAndNothingCrashes) {
  Bus bus("memq://");
  for (const std::string bad : {"*", "IMU(", "[", "a{2,1}"}) {
    try {
      bus.subscribe_raw(bad, [](const std::string&, const uint8_t*, int) {});
      ADD_FAILURE() << "'" << bad << "' accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("'" + bad + "'"), std::string::npos) << e.what();
    }
    EXPECT_THROW(bus.subscribe<ldv_lcm::imu_sample_t>(bad, [](const ldv_lcm::imu_sample_t&, const std::string&) {}),
                 std::invalid_argument)
        << bad;
  }
  int delivered = 0;  // the bus still works, and a valid expression still matches what LCM matches
  bus.subscribe_raw("(IMU|GNSS_SOLUTION)", [&](const std::string&, const uint8_t*, int) { ++delivered; });
  ldv_lcm::imu_sample_t m{};
  ASSERT_TRUE(bus.publish("IMU", m));
  ASSERT_TRUE(bus.publish("IMU_PPS", m));
  while (bus.handle(0) > 0) {
  }
  EXPECT_EQ(delivered, 1);
}
