// imu_acq as a real process, its serial port a pty carrying the time-stamp unit's frames in real time
// with faults a serial line produces: frames with a corrupted CRC (a flipped payload bit, a flipped CRC
// byte), bursts of line noise between frames, and a frame cut short by the next one. Then: every good
// sample is published in sequence, every bad frame is counted (heartbeat malformed, fault bit 3,
// the lost device samples in dropped), nothing bad is published, and the service keeps running and
// exits cleanly. (test_imu_acq.cpp covers the clean stream and the stamps; test_faults.cpp the wrong
// LCM fingerprints on GNSS_PPS.)
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <ldv_lcm/imu_sample_t.hpp>
#include <ldv_lcm/service_status_t.hpp>
#include <optional>
#include <sstream>
#include <thread>

#include "common/bus/bus.hpp"
#include "common/formats/imu_device_frame.hpp"
#include "tests/integration/child_process.hpp"
#include "tests/integration/pty_pair.hpp"

using namespace ldv;

namespace {
const std::string kUrl = "udpm://239.255.76.67:7667?ttl=0";
constexpr double kRate_hz = 200.0;
constexpr int kSamples = 1200;  // 6 s
}  // namespace

TEST(ImuAcqBadFrames, GivenCorruptedFramesAndLineNoise_ThenGoodSamplesPublishedBadOnesCountedAndStillRunning) {
  test::PtyPair pty;
  const std::string cfg = (std::filesystem::temp_directory_path() / ("imu_acq_bad_" + std::to_string(::getpid()) + ".yaml")).string();
  std::ofstream(cfg) << "bus_url: \"" << kUrl << "\"\ninput:\n  type: serial\n  serial: {device: " << pty.slave_path()
                     << ", baud: 460800}\nprotocol: tsu\ntsu: {counter_hz: 10.0e6}\nsample_rate_hz: 200\npps: {source: none}\n";
  auto svc = std::make_unique<test::ChildProcess>(std::string(LDV_BIN_DIR) + "/imu_acq", std::vector<std::string>{"--config", cfg});
  Bus bus(kUrl);
  std::vector<ldv_lcm::imu_sample_t> imu;
  std::optional<ldv_lcm::service_status_t> status;
  SequenceTracker seq;
  bus.subscribe<ldv_lcm::imu_sample_t>("IMU", [&](const ldv_lcm::imu_sample_t& m, const std::string&) {
    seq.observe(m.seq);
    imu.push_back(m);
  }, 10000);
  bus.subscribe<ldv_lcm::service_status_t>("STATUS_IMU_ACQ", [&](const ldv_lcm::service_status_t& m, const std::string&) { status = m; });
  // Handles the bus until pred() holds or timeout_s passes (a loaded machine only makes it slower).
  auto spin_until = [&](auto pred, double timeout_s) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    while (!pred() && std::chrono::steady_clock::now() < end) bus.handle(5);
    return pred();
  };
  const auto t_wait = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  // Until the port is open (fault bit 0 clear): bytes buffered before the open are stale and dropped.
  // Any heartbeat with fault bit 0 clear proves the port open (it is opened, and its stale input flushed,
  // before READY and the first heartbeat): writing earlier would lose the first bytes to that flush.
  while (!(status && (status->fault_bits & 1) == 0) && std::chrono::steady_clock::now() < t_wait) bus.handle(10);
  ASSERT_TRUE(status) << "no heartbeat";

  // When 6 s of frames arrive, every 40th with a flipped payload bit, every 97th with a flipped CRC
  // byte, 50 bytes of line noise (no sync byte) every 100th, and every 150th cut short
  int bad_crc = 0, cut = 0, noise_bursts = 0;
  std::thread device([&] {
    const auto start = std::chrono::steady_clock::now();
    for (int k = 0; k < kSamples; ++k) {
      std::this_thread::sleep_until(start + std::chrono::duration<double>(k / kRate_hz));
      imu_device::ImuSampleFrame f;
      f.counter = static_cast<uint32_t>(1000000u + k * 50000u);
      f.sequence = static_cast<uint16_t>(k);
      f.dvel_lsb = {k, 0, -49033250};  // x carries the sample number
      std::vector<uint8_t> bytes;
      imu_device::append_frame(bytes, f);
      if (k % 40 == 39) {
        bytes[10] ^= 0x04;
        ++bad_crc;
      } else if (k % 97 == 96) {
        bytes.back() ^= 0xFF;
        ++bad_crc;
      } else if (k % 150 == 149) {
        bytes.resize(bytes.size() / 2);  // the next frame's sync bytes follow at once
        ++cut;
      }
      if (k % 100 == 50) {
        for (int i = 0; i < 50; ++i) bytes.insert(bytes.begin(), static_cast<uint8_t>(0x10 + (i * 37) % 0x80));
        ++noise_bursts;
      }
      pty.write_all(bytes.data(), bytes.size());
    }
  });
  device.join();
  const int bad = bad_crc + cut;
  // Until a heartbeat has counted every bad frame (the last frame is a bad CRC, so everything before it is
  // out); the counts asserted below, not the sample count, so a lost sample fails at once, fault bit still set
  spin_until([&] { return status && status->malformed >= bad_crc && status->dropped >= bad - 1; }, 30.0);

  // Then exactly the good samples are published, in sequence, none of the bad ones
  ASSERT_TRUE(status);
  std::printf("[ imu_acq bad frames ] sent %d frames: %d bad CRC, %d cut short, %d noise bursts; published %zu samples "
              "(publisher gaps %lld); heartbeat: received %lld, malformed %lld, dropped %lld, fault bits 0x%x, state %d\n",
              kSamples, bad_crc, cut, noise_bursts, imu.size(), static_cast<long long>(seq.lost()),
              static_cast<long long>(status->received), static_cast<long long>(status->malformed),
              static_cast<long long>(status->dropped), status->fault_bits, status->state);
  EXPECT_EQ(imu.size(), static_cast<size_t>(kSamples - bad));
  EXPECT_EQ(seq.lost(), 0);
  for (const auto& m : imu) {
    const long k = std::lround(m.dvel_b_mps[0] * 1e9);
    ASSERT_FALSE(k % 40 == 39 || k % 97 == 96 || k % 150 == 149) << "a bad frame was published: sample " << k;
    ASSERT_NEAR(m.dvel_b_mps[2], -0.04903325, 1e-12);
  }
  // And every bad frame is counted: CRC errors as malformed, the missing device samples as dropped
  EXPECT_GE(status->malformed, bad_crc);
  EXPECT_LE(status->malformed, bad);  // a frame cut short is a CRC error or a resync, never a sample
  EXPECT_GE(status->dropped, bad - 1);  // the last frame was bad: its loss shows with the next good one
  EXPECT_TRUE(status->fault_bits & (1 << 3)) << "bad-frames fault bit";
  EXPECT_EQ(status->state, 2) << "degraded";

  // And it still runs: more good frames are published, and SIGTERM stops it cleanly
  const size_t before = imu.size();
  std::vector<uint8_t> more;
  for (int k = kSamples; k < kSamples + 20; ++k) {
    imu_device::ImuSampleFrame f;
    f.counter = static_cast<uint32_t>(1000000u + k * 50000u);
    f.sequence = static_cast<uint16_t>(k);
    f.dvel_lsb = {k, 0, -49033250};
    imu_device::append_frame(more, f);
  }
  pty.write_all(more.data(), more.size());
  // Until the 20 are out and a heartbeat counts the last bad frame's lost sample (seen with the next good one)
  spin_until([&] { return imu.size() >= before + 20 && status->dropped >= bad; }, 30.0);
  EXPECT_EQ(imu.size(), before + 20);
  EXPECT_EQ(seq.lost(), 0);
  EXPECT_EQ(status->dropped, bad) << "every lost device sample counted";
  EXPECT_EQ(status->malformed, bad);
  svc->signal(SIGTERM);
  EXPECT_EQ(svc->wait_exit(3.0), 0);
}

// A device that speaks another protocol than the configured one (issue 46, 6: its bytes were dropped in silence,
// "frames 0, bad checksum 0"): NMEA text on a port configured for the time-stamp unit's frames.
TEST(ImuAcqBadFrames, GivenBytesOfAnotherProtocol_ThenNothingPublishedTheBadFramesFaultRaisedAndTheProtocolQuestioned) {
  test::PtyPair pty;
  const std::string base =
      (std::filesystem::temp_directory_path() / ("imu_acq_wrong_" + std::to_string(::getpid()))).string();
  std::ofstream(base + ".yaml") << "bus_url: \"" << kUrl
                                << "\"\ninput:\n  type: serial\n  serial: {device: " << pty.slave_path()
                                << ", baud: 460800}\nprotocol: tsu\ntsu: {counter_hz: 10.0e6}\nsample_rate_hz: "
                                   "200\npps: {source: none}\n";
  auto svc = std::make_unique<test::ChildProcess>(std::string(LDV_BIN_DIR) + "/imu_acq",
                                                  std::vector<std::string>{"--config", base + ".yaml"}, base + ".out",
                                                  base + ".err");
  Bus bus(kUrl);
  size_t published = 0;
  std::optional<ldv_lcm::service_status_t> status;
  bus.subscribe<ldv_lcm::imu_sample_t>("IMU", [&](const ldv_lcm::imu_sample_t&, const std::string&) { ++published; });
  bus.subscribe<ldv_lcm::service_status_t>("STATUS_IMU_ACQ",
                                           [&](const ldv_lcm::service_status_t& m, const std::string&) { status = m; });
  const auto until = [&](auto pred, double timeout_s) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    while (!pred() && std::chrono::steady_clock::now() < end) bus.handle(10);
    return pred();
  };
  ASSERT_TRUE(until([&] { return status && (status->fault_bits & 1) == 0; }, 30.0)) << "the port did not open";

  // When 3 s of GGA sentences arrive, 10 a second (about 750 bytes a second)
  const std::string gga = "$GPGGA,123519.00,4807.0380,N,01131.0000,E,4,12,0.9,545.4,M,46.9,M,1.0,0000*5C\r\n";
  size_t sent = 0;
  for (int k = 0; k < 30; ++k) {
    pty.write_all(reinterpret_cast<const uint8_t*>(gga.data()), gga.size());
    sent += gga.size();
    bus.handle(100);
  }
  // Then the bad-frames fault is raised and the service degraded, with nothing published
  ASSERT_TRUE(until([&] { return status && (status->fault_bits & (1 << 3)); }, 10.0)) << "no bad-frames fault";
  EXPECT_EQ(status->state, 2) << "degraded";
  EXPECT_EQ(published, 0u);
  // And the log asks whether the protocol is right, and the summary counts the bytes no frame holds
  svc->signal(SIGTERM);
  EXPECT_EQ(svc->wait_exit(3.0), 0);
  std::stringstream log;
  for (const char* stream : {".out", ".err"})
    if (std::ifstream in(base + stream); in && in.peek() != EOF) log << in.rdbuf();
  std::printf("[ imu_acq wrong protocol ] sent %zu bytes of NMEA; heartbeat fault bits 0x%x\n%s", sent,
              status->fault_bits, log.str().c_str());
  EXPECT_NE(log.str().find("is protocol right"), std::string::npos);
  EXPECT_NE(log.str().find("frames 0,"), std::string::npos);
  const size_t at = log.str().find("undecodable bytes ");
  ASSERT_NE(at, std::string::npos);
  EXPECT_GT(std::stoul(log.str().substr(at + 18)), sent / 2) << "the bytes of the sentences are counted";
}
