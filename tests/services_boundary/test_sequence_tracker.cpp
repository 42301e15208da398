// Gap counting from sequence numbers: one bad number must not inflate the dropped count for good.
#include <gtest/gtest.h>

#include "common/bus/bus.hpp"

using namespace ldv;

TEST(SequenceTracker, GivenOneHugeSequenceNumber_ThenNothingIsCountedLost) {
  SequenceTracker t;
  for (int64_t s = 0; s < 100; ++s) t.observe(s);
  t.observe(4'000'000'000'000);  // corrupt
  for (int64_t s = 100; s < 200; ++s) t.observe(s);
  EXPECT_EQ(t.lost(), 0);
  EXPECT_EQ(t.outliers(), 1);
  EXPECT_EQ(t.received(), 201);
}

TEST(SequenceTracker, GivenOneStrayZero_ThenNeitherAResetNorALoss) {
  SequenceTracker t;
  for (int64_t s = 0; s < 100; ++s) t.observe(s);
  t.observe(0);
  for (int64_t s = 100; s < 110; ++s) t.observe(s);
  EXPECT_EQ(t.lost(), 0);
  EXPECT_EQ(t.resets(), 0);
}

TEST(SequenceTracker, GivenARealGap_ThenItIsCountedWhenTheNextMessageConfirmsIt) {
  SequenceTracker t;
  for (int64_t s = 0; s < 10; ++s) t.observe(s);
  EXPECT_EQ(t.observe(15), 0);  // not yet believed
  EXPECT_EQ(t.observe(16), 5);  // confirmed: 10..14 lost
  EXPECT_EQ(t.lost(), 5);
}

TEST(SequenceTracker, GivenAPublisherRestart_ThenAResetNotALoss) {
  SequenceTracker t;
  for (int64_t s = 0; s < 500; ++s) t.observe(s);
  for (int64_t s = 0; s < 10; ++s) t.observe(s);
  EXPECT_EQ(t.resets(), 1);
  EXPECT_EQ(t.lost(), 0);
  // A confirmed jump beyond kMaxCountedGap is a restart with a new numbering, not a loss.
  t.observe(9 + SequenceTracker::kMaxCountedGap + 10);
  t.observe(9 + SequenceTracker::kMaxCountedGap + 11);
  EXPECT_EQ(t.resets(), 2);
  EXPECT_EQ(t.lost(), 0);
}
