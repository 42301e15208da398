// lcmtypes/wheel_speed_t.lcm: the generated type encodes and decodes every field (4 wheels), and its size
// stays far below LCM 1.3.1's fragmentation limit.
#include <gtest/gtest.h>

#include <vector>

#include "ldv_lcm/wheel_speed_t.hpp"

TEST(LcmWheelSpeed, FourWheelsRoundTrip) {
  ldv_lcm::wheel_speed_t m;
  m.seq = 42;
  m.gps_week = 2300;
  m.gps_sow_s = 345600.02;
  m.host_time_s = 1.7e9;
  m.latency_s = 0.015f;
  m.num_wheels = 4;
  m.wheel_id = {1, 2, 3, 4};
  m.speed_mps = {10.1, 10.3, 9.9, -0.2};
  m.counts = {1000, 1002, 998, -5};
  m.counts_per_m = 48.5;
  m.status = 0b011;
  std::vector<uint8_t> buf(static_cast<size_t>(m.getEncodedSize()));
  ASSERT_EQ(m.encode(buf.data(), 0, static_cast<int>(buf.size())), static_cast<int>(buf.size()));
  EXPECT_EQ(buf.size(), 8u + 45u + 17u * 4u);  // fingerprint + fixed fields + per wheel
  ldv_lcm::wheel_speed_t d;
  ASSERT_EQ(d.decode(buf.data(), 0, static_cast<int>(buf.size())), static_cast<int>(buf.size()));
  EXPECT_EQ(d.seq, 42);
  EXPECT_EQ(d.gps_week, 2300);
  EXPECT_EQ(d.gps_sow_s, 345600.02);
  EXPECT_EQ(d.latency_s, 0.015f);
  EXPECT_EQ(d.num_wheels, 4);
  EXPECT_EQ(d.wheel_id, m.wheel_id);
  EXPECT_EQ(d.speed_mps, m.speed_mps);
  EXPECT_EQ(d.counts, m.counts);
  EXPECT_EQ(d.counts_per_m, 48.5);
  EXPECT_EQ(d.status, 0b011);
  // A wrong type's bytes are refused by the fingerprint.
  buf[0] ^= 0xFF;
  EXPECT_LT(d.decode(buf.data(), 0, static_cast<int>(buf.size())), 0);
}
