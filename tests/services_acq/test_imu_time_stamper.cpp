// The stamper with a simulated oscillator 50 ppm off, 1 ms host jitter, NMEA-style (last-pulse)
// labels arriving hundreds of milliseconds after their edge, a missing pulse: flagged
// extrapolated stamps until the fit locks, then stamps within a microsecond of the truth.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "services/imu_acq/imu_time_stamper.hpp"
#include "services/imu_acq/timing_report.hpp"
#include "tests/services_acq/sim_oscillator.hpp"

using namespace ldv;
using namespace ldv::imu;

TEST(ImuTimeStamper, GivenA50ppmOscillatorAndLastPulseLabels_ThenSubMicrosecondStampsAfterLock) {
  test::SimOscillator osc;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> host_jitter_s(0.0, 1e-3);
  const GpsTime t0{2320, 116400.0};
  const double unix_minus_gps_s = kGpsEpochInUnixSeconds - 18.0;  // host clock is UTC
  auto host_at = [&](double t_s) { return t0.total_seconds() + t_s + unix_minus_gps_s + 2e-3 + host_jitter_s(rng); };

  StamperOptions o;
  o.fit.nominal_counter_hz = osc.nominal_hz;
  o.fit.counter_bits = 32;
  std::vector<JudgedEdge> edges;
  ImuTimeStamper stamper(o, [&](const JudgedEdge& e) { edges.push_back(e); });
  TimingReport report(0.01, 2e-7);

  const double rate_hz = 100.0;
  double sum2 = 0, max_err = 0;
  int locked = 0, extrapolated = 0;
  for (int k = 1; k <= 30 * 100; ++k) {
    const double t_s = k / rate_hz;
    const double whole = std::round(t_s);
    if (std::abs(t_s - whole) < 1e-9 && static_cast<int>(whole) != 12) {  // pulse 12 is missing
      stamper.on_pps_latch(osc.latch(whole), host_at(whole));
    }
    // The ZDA of that second arrives ~0.25 s after the edge.
    if (std::abs(t_s - (std::floor(t_s) + 0.25)) < 1e-9 && static_cast<int>(std::floor(t_s)) != 12) {
      gnss::PpsTimeLabel label;
      label.pulse_time = GpsTime::from_total_seconds(t0.total_seconds() + std::floor(t_s));
      label.refers = gnss::PpsTimeLabel::Refers::kLastPulse;
      stamper.on_label(label, host_at(t_s));
    }
    const double host = host_at(t_s);
    stamper.poll(host);
    const Stamp s = stamper.stamp(osc.latch(t_s), host);
    if (s.extrapolated) {
      ++extrapolated;
      EXPECT_EQ(locked, 0) << "a flagged stamp after lock at sample " << k;
      // The fallback is anchored to the host clock: milliseconds, not seconds, off.
      EXPECT_NEAR(s.time.total_seconds() - t0.total_seconds(), t_s, 0.05);
      report.break_chain();
      continue;
    }
    ++locked;
    report.add_locked_stamp(s.time);
    const double err = (s.time.week - t0.week) * kSecondsPerWeek + (s.time.sow_s - t0.sow_s) - t_s;
    sum2 += err * err;
    max_err = std::max(max_err, std::abs(err));
  }
  const double rms = std::sqrt(sum2 / locked);
  std::printf("[ stamper ] extrapolated %d, locked %d, stamp error RMS %.1f ns max %.1f ns, drift %.3f ppm, "
              "interval %.9f s +- %.1f ns, missing PPS %llu\n",
              extrapolated, locked, rms * 1e9, max_err * 1e9, stamper.fit().frequency_offset_ppm(), report.mean_s(),
              report.std_s() * 1e9, static_cast<unsigned long long>(stamper.fit().counters().missing));
  EXPECT_GT(extrapolated, 0);
  EXPECT_LT(extrapolated, 5 * 100);  // locks within a few seconds
  EXPECT_LT(rms, 1e-6);
  EXPECT_LT(max_err, 2e-6);
  EXPECT_NEAR(stamper.fit().frequency_offset_ppm(), 50.0, 0.1);
  EXPECT_EQ(stamper.fit().counters().missing, 1u);
  EXPECT_NEAR(report.mean_s(), 0.01, 1e-9);
  EXPECT_LT(report.std_s(), 1e-6);
  const auto m = report.message(0, 0.0, stamper.fit(), 0);
  int in_bins = 0;
  for (int b : m.hist_count) in_bins += b;
  EXPECT_EQ(in_bins, static_cast<int>(report.intervals()));
  EXPECT_EQ(m.missing_pps, 1);
  ASSERT_FALSE(edges.empty());
  EXPECT_TRUE(edges.back().gps_second.has_value());
}

// A restart of imu_acq: the fit saved while locked (fit_state.hpp) is loaded by a new stamper 500 s later (the
// 32-bit counter has wrapped in between). Until new PPS edges arrive its stamps stay on GPS time (holdover,
// microseconds), not on the host clock; and when the device restarted its counter too, the saved fit is not
// used (host-clock stamps, flagged).
TEST(ImuTimeStamper, GivenAFitSavedBeforeARestart_ThenStampsStayOnGpsTimeUntilTheFitRelocks) {
  test::SimOscillator osc;
  const GpsTime t0{2320, 116400.0};
  const double unix_minus_gps_s = kGpsEpochInUnixSeconds - 18.0;
  auto host_at = [&](double t_s) { return t0.total_seconds() + t_s + unix_minus_gps_s + 3e-3; };
  StamperOptions o;
  o.fit.nominal_counter_hz = osc.nominal_hz;
  auto label_at = [&](double whole_s) {
    gnss::PpsTimeLabel label;
    label.pulse_time = GpsTime::from_total_seconds(t0.total_seconds() + whole_s);
    label.refers = gnss::PpsTimeLabel::Refers::kLastPulse;
    return label;
  };

  ImuTimeStamper before(o, nullptr);
  for (int k = 1; k <= 20 * 100; ++k) {
    const double t_s = k / 100.0;
    if (k % 100 == 0) {
      before.on_pps_latch(osc.latch(t_s), host_at(t_s));
      before.on_label(label_at(t_s), host_at(t_s + 0.25));
    }
    before.poll(host_at(t_s));
    before.stamp(osc.latch(t_s), host_at(t_s));
  }
  ASSERT_TRUE(before.fit().locked());
  const auto state = before.fit_state(host_at(20.0));
  ASSERT_TRUE(state.has_value());
  const std::string path = ::testing::TempDir() + "/pps_fit_state.yaml";
  save_fit_state(path, *state);
  const double restart_s = 520.0;  // counter phase + 5.2e9 counts: past the 2^32 wrap
  const auto loaded = load_fit_state(path, host_at(restart_s), 600.0);
  ASSERT_TRUE(loaded.has_value());
  EXPECT_FALSE(load_fit_state(path, host_at(restart_s), 300.0).has_value()) << "older than the maximum age";

  ImuTimeStamper after(o, nullptr);
  after.seed(*loaded);
  double max_err_s = 0.0;
  for (int k = 0; k < 100; ++k) {  // one second of samples, no PPS yet
    const double t_s = restart_s + k / 100.0;
    const Stamp s = after.stamp(osc.latch(t_s), host_at(t_s));
    EXPECT_TRUE(s.extrapolated && s.holdover);
    max_err_s = std::max(max_err_s, std::abs(s.time.total_seconds() - t0.total_seconds() - t_s));
  }
  std::printf("[ stamper ] after a 500 s restart gap, holdover stamps from the saved fit: max error %.2f us\n",
              max_err_s * 1e6);
  EXPECT_LT(max_err_s, 10e-6);

  // The device was power-cycled as well: its counter starts elsewhere, the saved fit does not apply.
  test::SimOscillator cold = osc;
  cold.phase_counts = 1000.0;
  ImuTimeStamper fresh(o, nullptr);
  fresh.seed(*loaded);
  const Stamp s = fresh.stamp(cold.latch(restart_s), host_at(restart_s));
  EXPECT_TRUE(s.extrapolated);
  EXPECT_FALSE(s.holdover);
  EXPECT_NEAR(s.time.total_seconds() - t0.total_seconds(), restart_s, 0.05);  // the host clock
}
