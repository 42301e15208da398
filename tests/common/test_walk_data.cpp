// The real walk (../shared/data/drives/walk_0827): IMU CSV + RTKLIB time tags -> GPS-timed increments.
#include <gtest/gtest.h>

#include "common/formats/rtklib_time_tag.hpp"
#include "common/formats/tagged_imu_csv.hpp"
#include "common/time/gps_time.hpp"

using namespace ldv;

namespace {
const std::string kWalk = std::string(LDV_SHARED_DATA_DIR) + "/drives/walk_0827/";
}

TEST(WalkData, TagFileStartTimeIsTheRecordingStart) {
  const RtklibTimeTag tag = read_rtklib_time_tag(kWalk + "imu_1730.csv.tag");
  // The RTK solution of the same walk starts at 2025/08/28 17:30:39.749 GPST; the IMU log started
  // about a second later (host tick of the IMU file 1306 ms after the receiver file).
  const double pos_start = gps_from_calendar({2025, 8, 28, 17, 30, 39.749}).total_seconds();
  EXPECT_NEAR(tag.start_gps_s - pos_start, 1.2, 0.2);
  EXPECT_GT(tag.entries.size(), 9000u);
}

TEST(WalkData, ImuSamplesGetMonotonicGpsTimeWithTheDeviceRateAndSmallLatency) {
  TaggedImuCsvReport rep;
  const auto imu = read_tagged_imu_csv(kWalk + "imu_1730.csv", kWalk + "imu_1730.csv.tag", {}, &rep);
  ASSERT_GT(imu.size(), 20000u);
  // The first and the last line of the log are cut mid-line.
  EXPECT_GE(rep.skipped_lines, 1);
  EXPECT_LE(rep.skipped_lines, 2);
  // The device's "ms" counter runs about 2 % fast against the host tick (which tracks GPS time: the
  // receiver's tag file spans the same 133.9 s as its RTK solution): a cheap MCU oscillator. The fit
  // absorbs it, so a mean 6.56 counter units between samples is 6.43 ms of GPS time (155 Hz).
  double mean_dt = 0;
  for (size_t i = 1; i < imu.size(); ++i) {
    ASSERT_GT(imu[i].t_s, imu[i - 1].t_s);
    mean_dt += imu[i].dt_s;
  }
  mean_dt /= (imu.size() - 1);
  EXPECT_NEAR(mean_dt, 0.00643, 0.0001);
  EXPECT_NEAR(rep.counter_rate_error_ppm, -20500.0, 500.0);
  // Host reads arrive in chunks: the median delay behind the earliest possible arrival stays below
  // a tenth of a second.
  EXPECT_LT(rep.median_latency_s, 0.1);
  EXPECT_LT(rep.p99_latency_s, 0.1);
  // Static at the start: |f| = 1 g within the sensor's few-percent scale error.
  const double f0 = imu[10].dvel_b_mps.norm() / imu[10].dt_s;
  EXPECT_NEAR(f0, 9.80665, 0.3);
}
