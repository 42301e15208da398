// The property the fuzzer checks (tests/fuzz/fuzz_bus_gate.cpp), on fixed random streams in the default suite:
// whatever valid-but-extreme messages fusion receives across a GPS week rollover (fields at 1e30, NaN, 1e-300,
// weeks moved, times of week past the week, duplicates, swaps, losses, plausible position jumps), NAV stays
// finite and plausible, only goes forward, and comes again by the end of the clean last 2 s.
#include <gtest/gtest.h>

#include <random>

#include "tests/fuzz/hostile_stream.hpp"

using namespace ldv;

namespace {
// A script touching about `fraction` of the messages (selectors 16-23 leave a message as it is).
std::vector<uint8_t> script(unsigned seed, double fraction) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> byte(0, 255), touched(0, 15), untouched(16, 23);
  std::bernoulli_distribution touch(fraction);
  std::vector<uint8_t> s;
  for (int k = 0; k < 2600; ++k) {
    s.push_back(static_cast<uint8_t>(touch(rng) ? touched(rng) : untouched(rng)));
    s.push_back(static_cast<uint8_t>(byte(rng)));
  }
  return s;
}
}  // namespace

TEST(HostileStreams, GivenTheCleanStreamAcrossAWeekRollover_ThenNavCoversItAll) {
  const fuzz::StreamOutcome r = fuzz::replay_hostile_stream(fuzz::clean_stream());
  EXPECT_EQ(r.refused, 0);
  EXPECT_GT(r.nav, 1990);  // 20 s at 100 Hz
  EXPECT_TRUE(r.finite_and_plausible);
  EXPECT_TRUE(r.times_increase);
  EXPECT_NEAR(r.last_nav_t_s, r.last_imu_t_s, 1e-6);
  EXPECT_GT(r.last_nav_t_s, kSecondsPerWeek) << "into the next week";
}

TEST(HostileStreams, GivenRandomHostileStreams_ThenNavStaysFinitePlausibleForwardAndComesBack) {
  for (const double fraction : {0.01, 0.1, 0.5}) {
    for (unsigned seed = 1; seed <= 10; ++seed) {
      const std::vector<uint8_t> s = script(seed, fraction);
      const fuzz::StreamOutcome r = fuzz::replay_hostile_stream(fuzz::hostile_stream(s.data(), s.size()));
      EXPECT_TRUE(r.finite_and_plausible) << "fraction " << fraction << " seed " << seed;
      EXPECT_TRUE(r.times_increase) << "fraction " << fraction << " seed " << seed;
      EXPECT_GT(r.last_nav_t_s, r.last_imu_t_s - 0.5)
          << "NAV stopped: fraction " << fraction << " seed " << seed << ", last NAV " << r.last_nav_t_s
          << ", last IMU " << r.last_imu_t_s << ", refused " << r.refused;
    }
  }
}
