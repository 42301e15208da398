// The real walk (../shared/data/drives/walk_0827): IMU CSV + RTKLIB time tags -> GPS-timed increments.
#include <gtest/gtest.h>

#include <algorithm>

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

// RTKLIB writes each (tick, position) pair after the chunk (stream.c, writefile): the position is where the chunk
// ends. The real file says so at both ends: its first pair is at byte 835, not 0 (the first chunk's 835 bytes), and
// its last at the file's end (1,001,983 bytes counted with CRLF): read as chunk starts, the first 835 bytes would
// have no tag and the last chunk no bytes.
TEST(WalkData, TagPositionsAreWhereTheirChunksEnd) {
  const RtklibTimeTag tag = read_rtklib_time_tag(kWalk + "imu_1730.csv.tag");
  ASSERT_GE(tag.entries.size(), 3u);
  EXPECT_EQ(tag.entries.front().file_pos, 835u);
  EXPECT_EQ(tag.entries.back().file_pos, 981527u + 20456u);
  const double t0_s = tag.start_gps_s;  // 1.4e9 s: differences hold to 2.4e-7 s
  EXPECT_NEAR(tag.reception_gps_s(0) - t0_s, tag.entries[0].tick_ms * 1e-3, 1e-6);
  EXPECT_NEAR(tag.reception_gps_s(834) - t0_s, tag.entries[0].tick_ms * 1e-3, 1e-6);
  // byte 835 is in the next chunk that ends beyond it
  const auto next =
      std::find_if(tag.entries.begin(), tag.entries.end(), [](const auto& e) { return e.file_pos > 835; });
  ASSERT_NE(next, tag.entries.end());
  EXPECT_NEAR(tag.reception_gps_s(835) - t0_s, next->tick_ms * 1e-3, 1e-6);
}

TEST(WalkData, ImuSamplesGetMonotonicGpsTimeOnTheDeviceCounter) {
  TaggedImuCsvReport rep;
  const auto imu = read_tagged_imu_csv(kWalk + "imu_1730.csv", kWalk + "imu_1730.csv.tag", {}, &rep);
  ASSERT_GT(imu.size(), 20000u);
  // The first and the last line of the log are cut mid-line.
  EXPECT_GE(rep.skipped_lines, 1);
  EXPECT_LE(rep.skipped_lines, 2);
  // The tag file counts CRLF line ends (its last position, 1,001,983, is the stored 981,527 bytes plus one CR
  // for each of the 20,456 lines); the CSV as stored has LF. Matched in that convention the host tick (which
  // tracks GPS time: the receiver's tag file spans the same time as its RTK solution) and the device counter
  // run at the same rate within a crystal's ppm; read as LF they once seemed 2.05 % apart.
  EXPECT_EQ(rep.line_ends.rfind("CRLF", 0), 0u) << rep.line_ends;
  EXPECT_EQ(rep.crlf_added_bytes, 20456);
  EXPECT_NEAR(rep.host_rate_error_ppm, 0.0, 100.0);
  EXPECT_NEAR(rep.counter_rate, 1.0, 100e-6);
  EXPECT_NE(rep.rate_source.find("host reception times"), std::string::npos) << rep.rate_source;
  EXPECT_EQ(rep.dropped.total(), rep.skipped_lines);
  double mean_dt = 0;
  for (size_t i = 1; i < imu.size(); ++i) {
    ASSERT_GT(imu[i].t_s, imu[i - 1].t_s);
    mean_dt += imu[i].dt_s;
  }
  mean_dt /= (imu.size() - 1);
  EXPECT_NEAR(mean_dt, 0.00656, 0.0001);  // 6.56 counter ms between samples: 152 Hz
  // The offset comes from the first seconds of the log, which arrived promptly: the first sample is placed
  // within 0.15 s of the tag file's start time (it arrived 0.11 s after it).
  const RtklibTimeTag tag = read_rtklib_time_tag(kWalk + "imu_1730.csv.tag");
  EXPECT_NEAR(imu.front().t_s - imu.front().dt_s, GpsTime::from_total_seconds(tag.start_gps_s).sow_s, 0.15);
  // Static at the start: |f| = 1 g within the sensor's few-percent scale error.
  const double f0 = imu[10].dvel_b_mps.norm() / imu[10].dt_s;
  EXPECT_NEAR(f0, 9.80665, 0.3);
}

TEST(WalkData, AGivenCounterRateIsUsed) {
  TaggedImuCsvOptions o;
  o.counter_rate = 1.0 - 0.0205;
  TaggedImuCsvReport rep;
  const auto imu = read_tagged_imu_csv(kWalk + "imu_1730.csv", kWalk + "imu_1730.csv.tag", o, &rep);
  EXPECT_EQ(rep.rate_source, "given");
  double span = imu.back().t_s - imu.front().t_s;
  EXPECT_NEAR(span, 134.25 * o.counter_rate, 0.05);
}
