// The IMU device decoders: the time-stamp unit's frames (encoded with the shared encoder the
// simulator uses) and the MicroStrain 3DM-GX2 records.
#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include "services/imu_acq/protocols/gx2_decoder.hpp"
#include "services/imu_acq/protocols/tsu_decoder.hpp"

using namespace ldv;
using namespace ldv::imu;

TEST(TsuDecoder, GivenSamplesAndLatchesInOddChunks_ThenSiIncrementsCountersAndLostSamples) {
  std::vector<std::uint8_t> bytes;
  for (std::uint16_t k = 0; k < 10; ++k) {
    if (k == 4) continue;  // lost on the device side: a sequence gap
    imu_device::ImuSampleFrame f;
    f.counter = 0xFFFFFF00u + 100000u * k;  // wraps during the run
    f.sequence = static_cast<std::uint16_t>(65530 + k);  // and so does the sequence
    f.dtheta_lsb = {1000, -2000, 3000};
    f.dvel_lsb = {-98066500, 0, 7};
    f.status = k == 9 ? imu_device::kStatusOverRange : 0;
    imu_device::append_frame(bytes, f);
    if (k == 5) imu_device::append_frame(bytes, imu_device::PpsLatchFrame{12345u, 7});
  }
  TsuDecoder d(10e6);
  std::vector<DeviceSample> samples;
  std::vector<DevicePpsLatch> latches;
  d.on_sample([&](const DeviceSample& s) { samples.push_back(s); });
  d.on_pps([&](const DevicePpsLatch& p) { latches.push_back(p); });
  for (std::size_t i = 0; i < bytes.size(); i += 5) d.feed(std::span(bytes).subspan(i, std::min<std::size_t>(5, bytes.size() - i)));
  ASSERT_EQ(samples.size(), 9u);
  ASSERT_EQ(latches.size(), 1u);
  EXPECT_EQ(latches[0].counter, 12345u);
  EXPECT_NEAR(samples[0].dtheta_b_rad.y(), -2e-6, 1e-18);
  EXPECT_NEAR(samples[0].dvel_b_mps.x(), -0.0980665, 1e-15);
  EXPECT_TRUE(samples[8].device_error);
  EXPECT_FALSE(samples[0].device_error);
  EXPECT_EQ(d.counters().lost_samples, 1u);
  EXPECT_EQ(d.counters().frames, 10u);
  EXPECT_EQ(d.counters().bad_checksum, 0u);
}

TEST(TsuDecoder, GivenACorruptedFrameAndGarbage_ThenCountedAndTheNeighboursSurvive) {
  std::vector<std::uint8_t> bytes{0x00, 0xA5, 0x13, 0x37};
  imu_device::ImuSampleFrame f;
  for (std::uint16_t k = 0; k < 3; ++k) {
    f.sequence = k;
    const std::size_t start = bytes.size();
    imu_device::append_frame(bytes, f);
    if (k == 1) bytes[start + 10] ^= 0x40;  // a flipped bit
  }
  TsuDecoder d;
  int n = 0;
  d.on_sample([&](const DeviceSample&) { ++n; });
  d.feed(bytes);
  EXPECT_EQ(n, 2);
  EXPECT_EQ(d.counters().bad_checksum, 1u);
  EXPECT_GT(d.counters().skipped_bytes, 3u);
  EXPECT_EQ(d.counters().lost_samples, 1u);  // the corrupted one is missing from the sequence
}

TEST(Gx2Frame, GivenEveryRecordType_ThenRoundTripAndChecksumGuards) {
  for (std::uint8_t cmd : {gx2::kAccelRate, gx2::kDeltaAngleVelocity, gx2::kAccelRateOrientation, gx2::kAccelRateMag,
                           gx2::kAccelRateMagOrientation}) {
    auto bytes = gx2::encode_record(cmd, {0.5f, -1.0f, 0.25f}, {0.01f, 0.02f, -0.03f}, 0xDEADBEEF);
    ASSERT_EQ(bytes.size(), *gx2::record_bytes(cmd));
    const auto r = gx2::parse_record(bytes);
    ASSERT_TRUE(r) << int(cmd);
    EXPECT_EQ(r->timer, 0xDEADBEEFu);
    if (r->is_delta()) {
      EXPECT_FLOAT_EQ(r->first[1], -1.0f);   // delta angle
      EXPECT_FLOAT_EQ(r->second[2], -0.03f); // delta velocity
    } else {
      EXPECT_FLOAT_EQ(r->second[1], -1.0f);  // acceleration (first on the wire)
      EXPECT_FLOAT_EQ(r->first[2], -0.03f);  // angular rate
    }
    bytes[5] ^= 1;
    EXPECT_FALSE(gx2::parse_record(bytes));
  }
  EXPECT_EQ(gx2::start_continuous_command(0xC2), (std::vector<std::uint8_t>{0xC4, 0xC1, 0x29, 0xC2}));
}

TEST(Gx2Decoder, GivenRateRecordsBehindGarbage_ThenIncrementsFromTheTimerInterval) {
  std::vector<std::uint8_t> bytes{0xC2, 0x00, 0x11, 0xCB, 0x42};  // garbage that starts like records
  const double timer_hz = gx2::kTimerHz;
  const std::uint32_t t0 = 0xFFFF0000u;  // the timer wraps between the records
  for (int k = 0; k < 3; ++k) {
    const auto r = gx2::encode_record(gx2::kAccelRate, {0.0f, 0.0f, -1.0f}, {0.1f, 0.0f, 0.0f},
                                      t0 + static_cast<std::uint32_t>(k * 0.01 * timer_hz));
    bytes.insert(bytes.end(), r.begin(), r.end());
  }
  Gx2Decoder d(timer_hz, 0.01);
  std::vector<DeviceSample> s;
  d.on_sample([&](const DeviceSample& x) { s.push_back(x); });
  for (std::size_t i = 0; i < bytes.size(); i += 13) d.feed(std::span(bytes).subspan(i, std::min<std::size_t>(13, bytes.size() - i)));
  ASSERT_EQ(s.size(), 3u);
  EXPECT_NEAR(s[2].dtheta_b_rad.x(), 0.1 * 0.01, 1e-8);
  EXPECT_NEAR(s[2].dvel_b_mps.z(), -9.80665 * 0.01, 1e-7);
  EXPECT_GE(d.counters().skipped_bytes, 5u);
  EXPECT_EQ(d.counters().frames, 3u);
}

TEST(Gx2Decoder, GivenDeltaRecords_ThenIncrementsAsSentInSi) {
  const auto r = gx2::encode_record(gx2::kDeltaAngleVelocity, {1e-3f, 0, 0}, {0, 0, -0.01f}, 1000);
  Gx2Decoder d;
  DeviceSample s;
  d.on_sample([&](const DeviceSample& x) { s = x; });
  d.feed(r);
  EXPECT_NEAR(s.dtheta_b_rad.x(), 1e-3, 1e-9);
  EXPECT_NEAR(s.dvel_b_mps.z(), -0.0980665, 1e-8);
  EXPECT_EQ(s.counter, 1000u);
}

// Found by the fuzzer (tests/fuzz/corpus/fuzz_imu_device/finding_gx2_nan_float): a record whose floats are NaN or
// infinite passes the 16-bit sum; its sample was handed out as a measurement. Now flagged as the device's error,
// its increments zeroed, its timer kept.
TEST(Gx2Decoder, GivenARecordWithANanOrInfiniteFloat_ThenTheSampleIsFlaggedAsADeviceError) {
  for (const float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
    const auto r = gx2::encode_record(gx2::kDeltaAngleVelocity, {1e-3f, bad, 0}, {0, 0, -0.01f}, 2000);
    Gx2Decoder d;
    std::vector<DeviceSample> out;
    d.on_sample([&](const DeviceSample& x) { out.push_back(x); });
    d.feed(r);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_TRUE(out[0].device_error);
    EXPECT_TRUE(out[0].dtheta_b_rad.allFinite() && out[0].dvel_b_mps.allFinite());
    EXPECT_EQ(out[0].counter, 2000u);
  }
}
