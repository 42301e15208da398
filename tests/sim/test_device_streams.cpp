// Device byte streams: the IMU time-stamp-unit frames decode back to the increments with the
// oscillator's counter, PPS latches once per GPS second, and NMEA sentences carry valid checksums.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <sstream>

#include "common/formats/imu_device_frame.hpp"
#include "common/formats/nmea_writer.hpp"
#include "sim/device_streams.hpp"
#include "sim_test_helpers.hpp"

using namespace ldv;
using namespace ldv::sim;
using namespace ldv::sim::test;

TEST(SimDeviceStreams, Crc16IsTheCcittFalseCheckValue) {
  const std::string s = "123456789";
  EXPECT_EQ(imu_device::crc16_ccitt(reinterpret_cast<const uint8_t*>(s.data()), s.size()), 0x29B1);
}

TEST(SimDeviceStreams, ImuFramesDecodeToTheIncrementsAndTheCounterRunsAtTheOscillatorRate) {
  // Given 30 s at 100 Hz and a 10 MHz counter 25 ppm fast, no latch jitter
  SimRequest q;
  q.grade = "hg1700-typical";
  q.scenario = "turns";
  q.duration_s = 30;
  q.imu_rate_hz = 100;
  const SimResult r = simulate(q);
  Oscillator osc;
  osc.phase_counts = 4294967296.0 - 5e6;  // wraps half a second into the run
  const DeviceStreams d = make_device_streams(r.imu, q.start_sow_s, q.gps_week, r.gnss, r.gnss_latency_s, 1.0, 0.08, 18,
                                              osc, 1, false);
  // When the byte stream is decoded in odd-sized chunks with one corrupted byte in the middle
  std::vector<uint8_t> bytes = d.imu_bytes;
  const size_t corrupt_at = bytes.size() / 2;
  bytes[corrupt_at] ^= 0x40;
  imu_device::FrameDecoder dec;
  std::vector<imu_device::ImuSampleFrame> samples;
  std::vector<imu_device::PpsLatchFrame> pps;
  for (size_t i = 0; i < bytes.size(); i += 37)
    for (auto& f : dec.push(bytes.data() + i, std::min<size_t>(37, bytes.size() - i))) {
      if (auto* s = std::get_if<imu_device::ImuSampleFrame>(&f)) samples.push_back(*s);
      if (auto* p = std::get_if<imu_device::PpsLatchFrame>(&f)) pps.push_back(*p);
    }
  // Then exactly one frame is lost to the CRC and the rest decode
  EXPECT_EQ(dec.crc_errors(), 1u);
  EXPECT_EQ(samples.size() + pps.size(), r.imu.size() + 31 - 1);
  // the PPS latches are 10e6 * (1 + 25e-6) counts apart, across the 32-bit wrap
  for (size_t i = 1; i < pps.size(); ++i) {
    const uint32_t diff = pps[i].counter - pps[i - 1].counter;
    if (pps[i].sequence == pps[i - 1].sequence + 1) {
      EXPECT_NEAR(diff, 10e6 * (1 + 25e-6), 1.0);
    }
  }
  // and the decoded increments reproduce the data to the LSB, with no drift in the sum.
  double sum_decoded = 0, sum_true = 0;
  for (const auto& s : samples) {
    if (s.sequence >= 1000) break;
    sum_decoded += s.dtheta_lsb[2] * imu_device::kDthetaLsb_rad;
    sum_true += r.imu[s.sequence].dtheta_b_rad.z();
  }
  EXPECT_NEAR(sum_decoded, sum_true, imu_device::kDthetaLsb_rad);
  EXPECT_NEAR(samples[10].dvel_lsb[2] * imu_device::kDvelLsb_mps, r.imu[10].dvel_b_mps.z(), 2e-9);
}

TEST(SimDeviceStreams, NmeaSentencesHaveValidChecksumsAndCarryTheFixes) {
  SimRequest q;
  q.grade = "perfect";
  q.scenario = "drive";
  q.duration_s = 20;
  q.gnss_rate_hz = 2;
  q.outages = {{5.0, 2.0}};
  const SimResult r = simulate(q);
  const DeviceStreams d = make_device_streams(r.imu, q.start_sow_s, q.gps_week, r.gnss, r.gnss_latency_s, 2.0, 0.08, 18,
                                              Oscillator{}, 1, true);
  std::istringstream in(d.nmea_text);
  std::string line;
  int gga = 0, gga_no_fix = 0, zda = 0, gst = 0;
  while (std::getline(in, line)) {
    ASSERT_EQ(line.back(), '\r');
    line.pop_back();
    ASSERT_EQ(line[0], '$');
    const size_t star = line.find('*');
    ASSERT_NE(star, std::string::npos);
    // Then every checksum is the XOR of the characters between '$' and '*'
    uint8_t x = 0;
    for (size_t i = 1; i < star; ++i) x ^= static_cast<uint8_t>(line[i]);
    EXPECT_EQ(std::stoi(line.substr(star + 1), nullptr, 16), x) << line;
    if (line.rfind("$GNGGA", 0) == 0) (line.find(",0,00,") != std::string::npos ? gga_no_fix : gga)++;
    if (line.rfind("$GNZDA", 0) == 0) zda++;
    if (line.rfind("$GNGST", 0) == 0) gst++;
  }
  EXPECT_EQ(gga, static_cast<int>(r.gnss.size()));
  EXPECT_EQ(gga_no_fix, 4);  // 2 s outage at 2 Hz
  EXPECT_EQ(gst, gga);
  EXPECT_EQ(zda, 21);
  // The first GGA's latitude (ddmm.mmmmmmm) is the fix's, and its UTC is GPS time minus 18 s.
  const std::string first = d.nmea_text.substr(0, d.nmea_text.find('\n'));
  const double ddmm = std::stod(first.substr(17, 12));
  const double lat_deg = std::floor(ddmm / 100) + std::fmod(ddmm, 100) / 60;
  EXPECT_NEAR(lat_deg, r.gnss[0].pos.lat_rad * kRadToDeg, 1e-9);
  const CalendarTime utc = nmea::utc_from_gps(GpsTime{q.gps_week, q.start_sow_s}, 18);
  char hhmmss[16];
  std::snprintf(hhmmss, sizeof hhmmss, "%02d%02d%05.2f", utc.hour, utc.minute, utc.second);
  EXPECT_EQ(first.substr(7, 9), hhmmss);
  EXPECT_EQ(std::string(hhmmss), "235942.00");  // 2024/02/08 00:00:00 GPST = 2024/02/07 23:59:42 UTC
}
