// The kernel PPS reader. A real /dev/ppsN needs the kernel's PPS core (pps-ktimer or pps-ldisc
// modules); this build host has none (/sys/class/pps is absent, modules cannot be loaded in the
// container), so only the refusal of non-PPS devices is tested here.
#include <gtest/gtest.h>

#include <filesystem>

#include "services/imu_acq/timing/kernel_pps_source.hpp"

using namespace ldv::timing;

TEST(KernelPpsSource, GivenAMissingDevice_ThenOpenFailsWithTheReason) {
  std::string error;
  EXPECT_FALSE(KernelPpsSource::open("/dev/pps-does-not-exist", error));
  EXPECT_NE(error.find("pps-does-not-exist"), std::string::npos);
}

TEST(KernelPpsSource, GivenACharacterDeviceThatIsNotPps_ThenOpenRefusesIt) {
  std::string error;
  EXPECT_FALSE(KernelPpsSource::open("/dev/null", error));
  EXPECT_NE(error.find("not a PPS device"), std::string::npos) << error;
}

TEST(KernelPpsSource, GivenARealPpsDevice_ThenAnEdgeArrivesWithinTwoSeconds) {
  if (!std::filesystem::exists("/dev/pps0")) GTEST_SKIP() << "no /dev/pps0 (no kernel PPS source on this host)";
  std::string error;
  auto pps = KernelPpsSource::open("/dev/pps0", error);
  ASSERT_TRUE(pps) << error;
  auto e = pps->fetch(2.0, error);
  ASSERT_TRUE(e) << error;
  EXPECT_GT(e->assert_time_ns, 0);
}
