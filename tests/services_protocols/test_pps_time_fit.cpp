// PPS time-stamping against a simulated oscillator (DESIGN.md section 4, issue 4): a 10 MHz
// counter 50 ppm fast with aging and a temperature cycle, 32-bit so it wraps three times, exact
// latches at samples and PPS edges, 1 ms jitter on the host *arrival* of every message, missing
// pulses, late pulses and a wrong second label. Truth is the oscillator model itself.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <set>
#include <vector>

#include "services/imu_acq/timing/counter_unwrap.hpp"
#include "services/imu_acq/timing/pps_label_matcher.hpp"
#include "services/imu_acq/timing/pps_time_fit.hpp"
#include "services/imu_acq/timing/timing_statistics.hpp"

using namespace ldv;
using namespace ldv::timing;

namespace {
constexpr std::int64_t kStartSecond = 2320LL * 604800 + 116400;  // GPS second at simulation t = 0

struct Oscillator {
  double nominal_hz = 10e6;
  double offset = 50e-6;            // fractional frequency offset
  double aging_per_s = 1e-10;       // linear frequency drift
  double thermal_amplitude = 2e-8;  // temperature cycle
  double thermal_period_s = 300.0;
  double phase0_ticks = 4294967296.0 - 30.0 * 10e6;  // first wrap after ~30 s

  // Counter phase [ticks] at true time t [s]: the integral of the frequency.
  double phase(double t) const {
    const double w = 2 * std::numbers::pi / thermal_period_s;
    return phase0_ticks + nominal_hz * (t * (1 + offset) + 0.5 * aging_per_s * t * t +
                                        thermal_amplitude / w * (1 - std::cos(w * t)));
  }
  std::uint32_t latch(double t) const {
    return static_cast<std::uint32_t>(static_cast<std::uint64_t>(std::floor(phase(t))) & 0xffffffffu);
  }
};

struct Event {
  enum Kind { kEdge, kLabel, kSample } kind;
  double host_time_s;
  std::uint32_t counter = 0;
  std::int64_t label_second = 0;
  double true_time_s = 0;  // samples: truth
};

struct Scenario {
  double duration_s = 1200;
  double imu_interval_s = 0.0100005;  // IMU clock 50 ppm slow: the paper's measured mean
  double imu_sampling_jitter_s = 5e-6;
  double host_jitter_s = 1e-3;
  std::set<int> missing_edges{100, 101, 500};
  std::map<int, double> late_edges{{300, 150e-6}, {700, 0.2}};
  std::map<int, int> wrong_labels{{400, 1}};
  gnss::PpsTimeLabel::Refers label_kind = gnss::PpsTimeLabel::Refers::kLastPulse;
};

struct Outcome {
  double rms_error_s = 0, max_error_s = 0;
  std::size_t stamped = 0, unstamped = 0;
  std::vector<PpsEdgeVerdict> verdicts;
  PpsFitCounters counters;
  double frequency_offset_ppm = 0, true_offset_at_end_ppm = 0;
  double true_interval_mean_s = 0, true_interval_std_s = 0;
  SampleIntervalStatistics stats{0.01, 1e-6, 50};
};

Outcome simulate(const Scenario& sc, std::uint32_t seed = 1) {
  const Oscillator osc;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> host(0.0, sc.host_jitter_s), imu(0.0, sc.imu_sampling_jitter_s);
  std::vector<Event> events;
  for (int k = 1; k < sc.duration_s; ++k) {
    if (!sc.missing_edges.count(k)) {
      const double latch_t = k + (sc.late_edges.count(k) ? sc.late_edges.at(k) : 0.0);
      events.push_back({Event::kEdge, latch_t + 0.002 + host(rng), osc.latch(latch_t)});
    }
    const std::int64_t label = kStartSecond + k + (sc.wrong_labels.count(k) ? sc.wrong_labels.at(k) : 0);
    // ZDA for second k after its edge; TIM-TP for second k just after the previous edge.
    const double label_t = sc.label_kind == gnss::PpsTimeLabel::Refers::kLastPulse ? k + 0.3 : k - 1 + 0.05;
    events.push_back({Event::kLabel, label_t + host(rng), 0, label});
  }
  std::vector<double> sample_times;
  for (double t0 = 0.0037, k = 0; t0 + k * sc.imu_interval_s < sc.duration_s; ++k) {
    const double t = t0 + k * sc.imu_interval_s + imu(rng);
    sample_times.push_back(t);
    events.push_back({Event::kSample, t + 0.001 + host(rng), osc.latch(t), 0, t});
  }
  std::stable_sort(events.begin(), events.end(),
                   [](const Event& a, const Event& b) { return a.host_time_s < b.host_time_s; });

  Outcome out;
  PpsTimeFit fit;
  PpsLabelMatcher matcher([&](std::uint64_t counter, std::optional<std::int64_t> second) {
    out.verdicts.push_back(fit.add_pps_edge(counter, second).verdict);
  });
  double sum2 = 0;
  for (const Event& e : events) {
    matcher.poll(e.host_time_s);
    if (e.kind == Event::kEdge) matcher.on_edge(e.counter, e.host_time_s);
    if (e.kind == Event::kLabel) {
      gnss::PpsTimeLabel label;
      label.pulse_time = GpsTime{static_cast<int>(e.label_second / 604800), double(e.label_second % 604800)};
      label.refers = sc.label_kind;
      matcher.on_label(label, e.host_time_s);
    }
    if (e.kind != Event::kSample) continue;
    const auto stamp = fit.stamp(e.counter);
    if (!stamp) {
      ++out.unstamped;
      continue;
    }
    // Error against the truth, in week/sow to keep sub-nanosecond resolution.
    const double err = (stamp->week * 604800.0 - static_cast<double>(kStartSecond)) + stamp->sow_s - e.true_time_s;
    sum2 += err * err;
    out.max_error_s = std::max(out.max_error_s, std::abs(err));
    ++out.stamped;
    out.stats.add_stamp(*stamp);
  }
  out.rms_error_s = std::sqrt(sum2 / static_cast<double>(out.stamped));
  out.counters = fit.counters();
  out.frequency_offset_ppm = fit.frequency_offset_ppm();
  const double t_end = sc.duration_s, w = 2 * std::numbers::pi / osc.thermal_period_s;
  out.true_offset_at_end_ppm =
      (osc.offset + osc.aging_per_s * t_end + osc.thermal_amplitude * std::sin(w * t_end)) * 1e6;
  double m = 0, m2 = 0;
  std::sort(sample_times.begin(), sample_times.end());
  for (std::size_t i = 1; i < sample_times.size(); ++i) m += sample_times[i] - sample_times[i - 1];
  m /= static_cast<double>(sample_times.size() - 1);
  for (std::size_t i = 1; i < sample_times.size(); ++i) m2 += std::pow(sample_times[i] - sample_times[i - 1] - m, 2);
  out.true_interval_mean_s = m;
  out.true_interval_std_s = std::sqrt(m2 / static_cast<double>(sample_times.size() - 2));
  return out;
}

void report(const char* name, const Outcome& o) {
  const auto& c = o.counters;
  std::printf("[ %s ] stamped %zu (before lock %zu): error RMS %.1f ns, max %.1f ns; fitted offset %.4f ppm (truth at the end %.4f ppm)\n"
              "[ %s ] PPS edges %llu accepted %llu missing %llu late %llu spurious %llu wrong labels %llu "
              "unlabelled %llu reacquisitions %llu\n[ %s ] %s (truth %.7f s +- %.3f us)\n",
              name, o.stamped, o.unstamped, o.rms_error_s * 1e9, o.max_error_s * 1e9, o.frequency_offset_ppm, o.true_offset_at_end_ppm, name,
              (unsigned long long)c.edges, (unsigned long long)c.accepted, (unsigned long long)c.missing,
              (unsigned long long)c.late, (unsigned long long)c.spurious, (unsigned long long)c.wrong_labels,
              (unsigned long long)c.unlabelled, (unsigned long long)c.reacquisitions, name, o.stats.summary().c_str(),
              o.true_interval_mean_s, o.true_interval_std_s * 1e6);
}
}  // namespace

TEST(CounterUnwrap, GivenReadingsAcrossTheWrap_ThenTheyExtendMonotonically) {
  const std::int64_t ref = 4294967290;  // 6 ticks before the 32-bit wrap
  EXPECT_EQ(unwrap_nearest(3, ref, 32), 4294967299);      // after the wrap
  EXPECT_EQ(unwrap_nearest(4294967280u, ref, 32), 4294967280);  // slightly before ref
  // A 1000 s gap at 10 MHz is 2.3 wraps: only the expected tick count can resolve it.
  const std::int64_t later = ref + 10'000'000'000LL;
  EXPECT_EQ(unwrap_expected(static_cast<std::uint64_t>(later) & 0xffffffffu, ref, 1.00003e10, 32), later);
}

TEST(PpsTimeFit, GivenAnOscillator50PpmOffWithJitteredArrivalsMissingLateAndWrongLabels_ThenStampsAreSubMicrosecond) {
  const Outcome o = simulate(Scenario{});
  report("ZDA labels", o);
  EXPECT_LT(o.rms_error_s, 1e-6);   // the goal (the paper measured 9.45 us)
  EXPECT_LT(o.max_error_s, 1e-6);
  EXPECT_LT(o.unstamped, 400u);     // locked within ~3 s
  EXPECT_NEAR(o.frequency_offset_ppm, o.true_offset_at_end_ppm, 0.01);
  // Faults flagged one by one.
  EXPECT_EQ(o.counters.missing, 3u);
  EXPECT_EQ(o.counters.late, 2u);
  EXPECT_EQ(o.counters.wrong_labels, 1u);
  EXPECT_EQ(o.counters.spurious, 0u);
  EXPECT_EQ(o.counters.reacquisitions, 0u);
  // The paper's statistics from our own stamps match the simulated truth.
  EXPECT_NEAR(o.stats.mean_s(), o.true_interval_mean_s, 1e-9);
  EXPECT_NEAR(o.stats.std_s(), o.true_interval_std_s, 0.05 * o.true_interval_std_s);
  EXPECT_NEAR(o.stats.mean_s(), 0.0100005, 1e-8);
  EXPECT_EQ(o.stats.gaps(), 0u);
}

TEST(PpsTimeFit, GivenTimTpNextPulseLabels_ThenTheSameAccuracy) {
  Scenario sc;
  sc.label_kind = gnss::PpsTimeLabel::Refers::kNextPulse;
  const Outcome o = simulate(sc, 7);
  report("TIM-TP labels", o);
  EXPECT_LT(o.rms_error_s, 1e-6);
  EXPECT_EQ(o.counters.missing, 3u);
  EXPECT_EQ(o.counters.late, 2u);
  EXPECT_EQ(o.counters.wrong_labels, 1u);
}

TEST(PpsTimeFit, GivenAFitAcquiredOnAWrongLabel_WhenCorrectLabelsKeepDisagreeing_ThenItReacquires) {
  PpsTimeFit fit;
  const Oscillator osc;
  // The first three labels are one second off (e.g. a receiver that had not yet resolved time).
  for (int k = 1; k <= 3; ++k) fit.add_pps_edge(osc.latch(k), kStartSecond + k + 1);
  ASSERT_TRUE(fit.locked());
  std::vector<PpsEdgeVerdict> v;
  for (int k = 4; k <= 8; ++k) v.push_back(fit.add_pps_edge(osc.latch(k), kStartSecond + k).verdict);
  EXPECT_EQ(v[0], PpsEdgeVerdict::kAcceptedWrongLabel);
  EXPECT_EQ(v[1], PpsEdgeVerdict::kAcceptedWrongLabel);
  EXPECT_EQ(v[2], PpsEdgeVerdict::kReacquired);
  EXPECT_EQ(fit.counters().reacquisitions, 1u);
  ASSERT_TRUE(fit.locked());
  const auto t = fit.stamp(osc.latch(8.5));
  ASSERT_TRUE(t);
  EXPECT_NEAR((t->week * 604800.0 - kStartSecond) + t->sow_s, 8.5, 1e-6);
}

TEST(PpsTimeFit, GivenNoLabelsYet_ThenNothingIsStampedAndEdgesAreCountedUnlabelled) {
  PpsTimeFit fit;
  EXPECT_EQ(fit.add_pps_edge(123, std::nullopt).verdict, PpsEdgeVerdict::kUnlabelled);
  EXPECT_FALSE(fit.stamp(456));
  EXPECT_EQ(fit.counters().unlabelled, 1u);
}

TEST(SampleIntervalStatistics, GivenAKnownSequence_ThenMeanStdHistogramAndGaps) {
  SampleIntervalStatistics st(0.01, 1e-6, 5);
  GpsTime t{2320, 100.0};
  const double intervals[] = {0.010001, 0.009999, 0.010001, 0.009999, 0.030000};
  st.add_stamp(t);
  for (double d : intervals) {
    t.sow_s += d;
    st.add_stamp(t);
  }
  EXPECT_EQ(st.intervals(), 4u);
  EXPECT_NEAR(st.mean_s(), 0.01, 1e-12);
  EXPECT_NEAR(st.std_s(), 1e-6 * std::sqrt(4.0 / 3.0), 1e-10);
  EXPECT_EQ(st.gaps(), 1u);
  EXPECT_EQ(st.missing_samples(), 2u);
  EXPECT_EQ(st.histogram().bins[4] + st.histogram().bins[6], 4u);  // +-1 us bins around the centre
}
