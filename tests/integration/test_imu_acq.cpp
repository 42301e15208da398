// imu_acq as a real process in a private network namespace, driven through a pty with the
// time-stamp unit's byte stream (the shared encoder of common/formats/imu_device_frame.hpp), in
// real time: a 10 MHz counter 50 ppm fast that wraps during the run, 200 Hz samples, a PPS latch
// each second (one missing), and NMEA-style last-pulse labels on GNSS_PPS published by the test
// ~0.2 s after each edge. Checks the IMU rate, no gaps, stamp error against the truth, IMU_PPS,
// IMU_TIMING; then kill -9 and a fresh start on the running bus publishes again.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <thread>
#include <unordered_map>

#include <ldv_lcm/imu_sample_t.hpp>
#include <ldv_lcm/imu_timing_t.hpp>
#include <ldv_lcm/pps_event_t.hpp>
#include <ldv_lcm/service_status_t.hpp>

#include "common/bus/bus.hpp"
#include "tests/integration/bus_spin.hpp"
#include "common/formats/imu_device_frame.hpp"
#include "common/time/gps_time.hpp"
#include "tests/integration/child_process.hpp"
#include "tests/integration/pty_pair.hpp"
#include "tests/services_acq/sim_oscillator.hpp"

using namespace ldv;

namespace {
const std::string kUrl = "udpm://239.255.76.67:7667?ttl=0";
constexpr double kRate_hz = 200.0;
constexpr int kMissingPulse_s = 4;
const GpsTime kT0{2320, 116400.0};

// The simulated device and receiver, writing in real time from sample `first` to `last`.
struct DeviceSim {
  test::PtyPair& pty;
  test::SimOscillator osc;
  std::mutex truth_mutex;
  std::unordered_map<std::uint32_t, double> truth_s;  // raw counter -> true seconds since t0
  std::uint16_t sample_seq = 0, pps_seq = 0;

  explicit DeviceSim(test::PtyPair& p) : pty(p) {
    osc.ppm = 50.0;
    osc.phase_counts = 4294967296.0 - 3.5 * 10e6;  // the 32-bit counter wraps 3.5 s in
  }

  void run(int first, int last) {
    Bus labels(kUrl);
    int64_t label_seq = 0;
    const auto start = std::chrono::steady_clock::now();
    for (int k = first; k <= last; ++k) {
      const double t_s = k / kRate_hz;
      std::this_thread::sleep_until(start + std::chrono::duration<double>(t_s - first / kRate_hz));
      std::vector<std::uint8_t> bytes;
      const bool whole_second = k % static_cast<int>(kRate_hz) == 0;
      const int second = k / static_cast<int>(kRate_hz);
      if (whole_second && second != kMissingPulse_s) imu_device::append_frame(bytes, imu_device::PpsLatchFrame{osc.latch(t_s), pps_seq++});
      imu_device::ImuSampleFrame f;
      f.counter = osc.latch(t_s);
      f.sequence = sample_seq++;
      f.dvel_lsb = {0, 0, -49033250};  // 1 g over 5 ms, down
      {
        std::lock_guard<std::mutex> lock(truth_mutex);
        truth_s[f.counter] = t_s;
      }
      imu_device::append_frame(bytes, f);
      pty.write_all(bytes.data(), bytes.size());
      // The receiver's ZDA for this second, 0.2 s after its edge (none for the missing pulse).
      if (k % static_cast<int>(kRate_hz) == static_cast<int>(0.2 * kRate_hz) && second != kMissingPulse_s) {
        ldv_lcm::pps_event_t m{};
        m.seq = label_seq++;
        m.gps_week = kT0.week;
        m.gps_sow_s = kT0.sow_s + second;
        m.counter_raw = -1;
        m.flags = 0;  // last pulse
        labels.publish("GNSS_PPS", m);
      }
    }
  }
};

struct Listener {
  Bus bus{kUrl};
  std::vector<ldv_lcm::imu_sample_t> imu;
  std::vector<ldv_lcm::pps_event_t> pps;
  std::vector<ldv_lcm::imu_timing_t> timing;
  std::optional<ldv_lcm::service_status_t> status;
  SequenceTracker seq;
  Listener() {
    bus.subscribe<ldv_lcm::imu_sample_t>("IMU", [this](const ldv_lcm::imu_sample_t& m, const std::string&) {
      seq.observe(m.seq);
      imu.push_back(m);
    }, 10000);
    bus.subscribe<ldv_lcm::pps_event_t>("IMU_PPS", [this](const ldv_lcm::pps_event_t& m, const std::string&) { pps.push_back(m); });
    bus.subscribe<ldv_lcm::imu_timing_t>("IMU_TIMING", [this](const ldv_lcm::imu_timing_t& m, const std::string&) { timing.push_back(m); });
    bus.subscribe<ldv_lcm::service_status_t>("STATUS_IMU_ACQ", [this](const ldv_lcm::service_status_t& m, const std::string&) { status = m; });
  }
  template <class Pred>
  bool spin_until(Pred pred, double timeout_s) {
    return test::spin_until(bus, pred, timeout_s);
  }
};
}  // namespace

TEST(ImuAcqIntegration, GivenTheTimeStampUnitThroughAPtyWith50ppmAndPpsLabels_ThenRateNoGapsAndSubMicrosecondStamps) {
  test::PtyPair pty;
  const std::string cfg = (std::filesystem::temp_directory_path() / ("imu_acq_" + std::to_string(::getpid()) + ".yaml")).string();
  std::ofstream(cfg) << "bus_url: \"" << kUrl << "\"\ninput:\n  type: serial\n  serial: {device: " << pty.slave_path()
                     << ", baud: 460800}\nprotocol: tsu\ntsu: {counter_hz: 10.0e6}\nsample_rate_hz: 200\n"
                     << "pps: {source: device, label_refers: auto}\n";
  const std::string bin = std::string(LDV_BIN_DIR) + "/imu_acq";
  auto svc = std::make_unique<test::ChildProcess>(bin, std::vector<std::string>{"--config", cfg});
  Listener l;
  // Until the port is open (fault bit 0 clear): bytes buffered before the open are stale and dropped.
  // Any heartbeat with fault bit 0 clear proves the port open (it is opened, and its stale input flushed,
  // before READY and the first heartbeat): writing earlier would lose the first bytes to that flush.
  ASSERT_TRUE(l.spin_until([&] { return l.status.has_value() && (l.status->fault_bits & 1) == 0; }, 30.0))
      << "no heartbeat";

  // When 12 s of device bytes arrive in real time
  DeviceSim sim(pty);
  const int last = static_cast<int>(12 * kRate_hz);
  std::thread device([&] { sim.run(1, last); });
  l.spin_until([&] { return l.imu.size() >= static_cast<std::size_t>(last); }, 20.0);
  device.join();
  l.spin_until([&] { return false; }, 1.2);  // the last IMU_TIMING and heartbeat

  // Then every sample is published in sequence at the device rate
  ASSERT_EQ(l.imu.size(), static_cast<std::size_t>(last));
  EXPECT_EQ(l.seq.lost(), 0);
  const double host_span_s = l.imu.back().host_time_s - l.imu.front().host_time_s;
  const double rate_hz = (l.imu.size() - 1) / host_span_s;
  // And, once the fit has locked, stamped within a microsecond of the truth
  double sum2 = 0, max_err = 0;
  int locked = 0, flagged = 0;
  for (const auto& m : l.imu) {
    if (m.status & 1) {
      ++flagged;
      EXPECT_EQ(locked, 0) << "flagged stamp after lock, seq " << m.seq;
      continue;
    }
    ++locked;
    const double truth = sim.truth_s.at(static_cast<std::uint32_t>(m.counter_raw & 0xFFFFFFFF));
    const double err = (m.gps_week - kT0.week) * kSecondsPerWeek + (m.gps_sow_s - kT0.sow_s) - truth;
    sum2 += err * err;
    max_err = std::max(max_err, std::abs(err));
    EXPECT_NEAR(m.dvel_b_mps[2], -0.04903325, 1e-12);
  }
  const double rms = std::sqrt(sum2 / std::max(1, locked));
  ASSERT_FALSE(l.timing.empty());
  const auto& t = l.timing.back();
  int hist_total = 0;
  for (int c : t.hist_count) hist_total += c;
  std::printf("[ imu_acq via pty ] %zu samples at %.2f Hz (host), lost %lld, flagged before lock %d, locked %d: stamp "
              "error RMS %.1f ns, max %.1f ns\n",
              l.imu.size(), rate_hz, static_cast<long long>(l.seq.lost()), flagged, locked, rms * 1e9, max_err * 1e9);
  std::printf("[ IMU_TIMING ] interval %.9f s +- %.1f ns, drift %.3f ppm, fit residual RMS %.1f ns, missing PPS %d, "
              "late %d, histogram %d intervals in %d bins of %.1f us from %.6f s; IMU_PPS %zu\n",
              t.interval_mean_s, t.interval_std_s * 1e9, t.clock_drift_ppm, t.fit_residual_rms_s * 1e9, t.missing_pps,
              t.late_pps, hist_total, 32, t.hist_bin_s * 1e6, t.hist_lo_s, l.pps.size());
  EXPECT_NEAR(rate_hz, kRate_hz, 2.0);
  EXPECT_LT(flagged, static_cast<int>(6 * kRate_hz));
  EXPECT_GT(locked, static_cast<int>(5 * kRate_hz));
  EXPECT_LT(rms, 1e-6);
  EXPECT_NEAR(t.interval_mean_s, 1.0 / kRate_hz, 1e-8);
  EXPECT_LT(t.interval_std_s, 1e-6);
  EXPECT_NEAR(t.clock_drift_ppm, 50.0, 0.5);
  EXPECT_EQ(t.missing_pps, 1);
  EXPECT_GT(hist_total, 0);
  EXPECT_GE(l.pps.size(), 10u);  // 12 latches less the missing one (the last may await its label)
  ASSERT_TRUE(l.status);
  EXPECT_EQ(l.status->malformed, 0);
  EXPECT_EQ(l.status->dropped, 0);

  // When imu_acq is killed and started again on the running bus
  svc->signal(SIGKILL);
  EXPECT_EQ(svc->wait_exit(2.0), -SIGKILL);
  svc = std::make_unique<test::ChildProcess>(bin, std::vector<std::string>{"--config", cfg});
  const std::size_t before = l.imu.size();
  l.spin_until([&] { return false; }, 0.5);
  std::thread device2([&] { sim.run(last + 1, last + static_cast<int>(2 * kRate_hz)); });
  l.spin_until([&] { return l.imu.size() >= before + static_cast<std::size_t>(1.5 * kRate_hz); }, 30.0);
  device2.join();
  l.spin_until([&] { return false; }, 0.2);
  // Then it publishes again, a new sequence from 0
  ASSERT_GE(l.imu.size(), before + static_cast<std::size_t>(1.5 * kRate_hz));
  EXPECT_EQ(l.imu[before].seq, 0);
  std::printf("[ imu_acq restart ] %zu samples after kill -9 and restart\n", l.imu.size() - before);
  svc->signal(SIGTERM);
  EXPECT_EQ(svc->wait_exit(3.0), 0);
}
