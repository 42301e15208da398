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
