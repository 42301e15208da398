#pragma once
// Issue 14's study: `ldv allan`'s analysis on the paper's own sensors (the built-in grades from its Tables 4-9,
// per axis, read by the simulator's grade parser) at chosen record lengths, over seeds. Each seed simulates the
// six error channels of a static record through the simulator's IMU error model (the same code `ldv sim` runs;
// a static record's true increments only add constants, which the analysis removes), then analyses them as
// `ldv allan` does by default (bias model chosen by AIC) and with the paper's Gauss-Markov bias forced.
// Per axis and term it counts: value within the issue's tolerance, truth inside the reported 95 % interval, and
// for terms the paper did not identify, "resolved" (must never happen). Beside each term: the Cramer-Rao bound
// of the record (whittle_cramer_rao with the true levels), which says whether a tolerance is reachable.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "sim/imu_error_model.hpp"
#include "sim/imu_grade.hpp"
#include "toolbox/allan/analysis.hpp"
#include "toolbox/allan/avar_covariance.hpp"
#include "toolbox/allan/whittle_fit.hpp"

namespace ldv::allan::test {

// The issue's tolerances (relative) per term.
constexpr double kTolQ = 0.03, kTolN = 0.03, kTolGmSigma = 0.20, kTolGmT = 0.20, kTolK = 0.30, kTolR = 0.30;

enum class PaperTerm { kQ, kN, kGmSigma, kGmT, kK, kR, kCount };
inline const char* term_name(PaperTerm t) {
  static const char* names[] = {"Q", "N", "GM sigma", "GM T", "K", "R"};
  return names[static_cast<int>(t)];
}
inline double tolerance(PaperTerm t) {
  static const double tol[] = {kTolQ, kTolN, kTolGmSigma, kTolGmT, kTolK, kTolR};
  return tol[static_cast<int>(t)];
}

// One channel's true terms in SI of the rate (0: absent).
struct AxisTruth {
  std::string channel;
  std::array<double, static_cast<int>(PaperTerm::kCount)> value{};
  double operator[](PaperTerm t) const { return value[static_cast<int>(t)]; }
};

inline std::vector<AxisTruth> axes_of(const sim::ImuGrade& g) {
  std::vector<AxisTruth> axes;
  const char* xyz = "xyz";
  for (int sensor = 0; sensor < 2; ++sensor) {
    const sim::TriadErrorModel& m = sensor == 0 ? g.gyro : g.accel;
    for (int i = 0; i < 3; ++i) {
      AxisTruth a;
      a.channel = std::string(sensor == 0 ? "gyro_" : "accel_") + xyz[i];
      a.value = {m.quantization_Q[i], m.white_N[i],
                 m.instability_B[i],  m.instability_B[i] > 0 ? m.instability_T_s[i] : 0.0,
                 m.rate_rw_K[i],      std::fabs(m.ramp_R[i])};
      axes.push_back(a);
    }
  }
  return axes;
}

// The grade's in-run terms as the simulator's sensor model (no turn-on constants: they are a mean).
inline sim::TriadSensorModel in_run_model(const sim::TriadErrorModel& m) {
  sim::TriadSensorModel s;
  if (m.instability_B.maxCoeff() > 0) s.gauss_markov.push_back({m.instability_B, m.instability_T_s});
  s.rate_rw_K = m.rate_rw_K;
  s.ramp_R = m.ramp_R;
  s.white_N = m.white_N;
  s.quantization_Q = m.quantization_Q;
  s.quantization_rounding = m.quantization_rounding;
  return s;
}

// The six error channels of a static record (rates: increments over dt), as `ldv allan` reads them.
inline std::vector<PhaseSeries> simulate_static_channels(const sim::ImuGrade& g, double hours, double rate_hz,
                                                         uint64_t seed) {
  sim::ImuSensorModel model;
  model.gyro = in_run_model(g.gyro);
  model.accel = in_run_model(g.accel);
  sim::ImuErrorSimulator errors(model, seed);
  const double dt = 1.0 / rate_hz;
  const long n = std::lround(hours * 3600.0 * rate_hz);
  std::vector<std::vector<double>> y(6, std::vector<double>(n));
  ImuIncrement still;
  still.dt_s = dt;
  for (long k = 0; k < n; ++k) {
    still.t_s = (k + 1) * dt;
    const ImuIncrement out = errors.apply(still, (k + 0.5) * dt, Vec3::Zero(), Vec3::Zero());
    for (int i = 0; i < 3; ++i) {
      y[i][k] = out.dtheta_b_rad[i] / dt;
      y[3 + i][k] = out.dvel_b_mps[i] / dt;
    }
  }
  const std::vector<AxisTruth> axes = axes_of(g);
  std::vector<PhaseSeries> channels;
  for (int c = 0; c < 6; ++c)
    channels.push_back(phase_from_rates(std::move(y[c]), dt, axes[c].channel, c < 3 ? "rad/s" : "m/s^2"));
  return channels;
}

struct TermTally {
  int judged = 0, within = 0, covered = 0, resolved_absent = 0, absent_judged = 0;
  double rel_err_sq = 0.0;
  double reported_rel_sigma_sum = 0.0;  // the fit's own relative 1-sigma, summed over the judged seeds
  double crb = 0.0;                     // relative 1-sigma the record allows (0: not a density the bound covers)
  double rms() const { return judged ? std::sqrt(rel_err_sq / judged) : 0.0; }
  // The precision to judge reachability by: the Cramer-Rao bound; for R (not a density, no bound) the fit's own
  // sigma (the variance of the differences' mean under the other terms).
  double precision() const { return crb > 0 ? crb : judged ? reported_rel_sigma_sum / judged : 0.0; }
};

struct AxisTally {
  AxisTruth truth;
  std::array<TermTally, static_cast<int>(PaperTerm::kCount)> term{};
  int gm_chosen = 0, seeds = 0;
  TermTally& operator[](PaperTerm t) { return term[static_cast<int>(t)]; }
  const TermTally& operator[](PaperTerm t) const { return term[static_cast<int>(t)]; }
};

struct TermReading {
  double value = 0.0, sigma = 0.0, lo = 0.0, hi = 0.0;
  bool resolved = false;
};

// One paper term as the fit reports it; empty when the fit does not carry it (flat B chosen).
inline std::optional<TermReading> reading_of(const NoiseFit& f, PaperTerm t) {
  const TermEstimate& gm = f[ModelTerm::kGaussMarkov];
  if (t == PaperTerm::kGmT) {  // T is the GM term's shape, its interval from its profile likelihood
    if (!gm.in_model) return std::nullopt;
    return TermReading{gm.shape, gm.shape_sigma, gm.shape_lo, gm.shape_hi, gm.resolved};
  }
  static const ModelTerm kModelTerm[] = {ModelTerm::kQ,           ModelTerm::kN, ModelTerm::kGaussMarkov,
                                         ModelTerm::kGaussMarkov, ModelTerm::kK, ModelTerm::kR};
  const TermEstimate& e = f[kModelTerm[static_cast<int>(t)]];
  if (!e.in_model) return std::nullopt;
  return TermReading{e.value, e.sigma, e.lo, e.hi, e.resolved};
}

// An absent bias shows as resolved in either bias term.
inline bool any_bias_resolved(const NoiseFit& f) {
  return f[ModelTerm::kB].resolved || f[ModelTerm::kGaussMarkov].resolved;
}

inline void tally(AxisTally& a, const ChannelResult& r) {
  ++a.seeds;
  ASSERT_TRUE(r.fit.has_value()) << a.truth.channel << ": " << r.fit_error;
  const NoiseFit& f = *r.fit;
  a.gm_chosen += f[ModelTerm::kGaussMarkov].in_model;
  for (int i = 0; i < static_cast<int>(PaperTerm::kCount); ++i) {
    const auto t = static_cast<PaperTerm>(i);
    const double truth = a.truth[t];
    const std::optional<TermReading> seen = reading_of(f, t);
    TermTally& tt = a[t];
    if (truth <= 0) {  // absent in the paper's table: never resolved
      if (t == PaperTerm::kGmT) continue;
      ++tt.absent_judged;
      tt.resolved_absent += t == PaperTerm::kGmSigma ? any_bias_resolved(f) : (seen && seen->resolved);
      continue;
    }
    if (!seen) continue;
    ++tt.judged;
    tt.within += std::fabs(seen->value / truth - 1) <= tolerance(t);
    tt.covered += seen->lo <= truth && truth <= seen->hi;
    tt.rel_err_sq += std::pow(seen->value / truth - 1, 2);
    if (t == PaperTerm::kR) tt.reported_rel_sigma_sum += seen->sigma / truth;  // R's precision (no bound)
  }
}

inline void set_bounds(AxisTally& a, double tau0_s, long samples, double block_s) {
  NoiseLevels levels;
  levels.q = a.truth[PaperTerm::kQ], levels.n = a.truth[PaperTerm::kN], levels.k = a.truth[PaperTerm::kK];
  levels.gm_sigma = a.truth[PaperTerm::kGmSigma], levels.gm_t_s = a.truth[PaperTerm::kGmT];
  levels.r = a.truth[PaperTerm::kR];
  const RelativeBounds b = whittle_cramer_rao(levels, tau0_s, samples, block_s);
  a[PaperTerm::kQ].crb = b.q, a[PaperTerm::kN].crb = b.n, a[PaperTerm::kK].crb = b.k;
  a[PaperTerm::kGmSigma].crb = b.gm_sigma, a[PaperTerm::kGmT].crb = b.gm_t;
}

// A tolerance met in 90 % of seeds needs a relative 1-sigma of tolerance / 1.645 (normal errors).
inline bool reachable(const TermTally& t, PaperTerm term) { return 1.645 * t.precision() <= tolerance(term); }

struct PaperStudy {
  std::string grade;
  std::vector<AxisTally> by_default, gauss_markov;  // per channel
};

inline PaperStudy run_paper_study(const std::string& grade_name, double hours, double rate_hz, int seeds,
                                  int first_seed = 1) {
  const sim::ImuGrade grade = sim::imu_grade(grade_name);
  PaperStudy s;
  s.grade = grade_name;
  for (const AxisTruth& a : axes_of(grade)) {
    AxisTally t;
    t.truth = a;
    set_bounds(t, 1.0 / rate_hz, std::lround(hours * 3600.0 * rate_hz), FitOptions{}.likelihood_block_s);
    s.by_default.push_back(t), s.gauss_markov.push_back(t);
  }
  for (int seed = first_seed; seed < first_seed + seeds; ++seed) {
    const std::vector<PhaseSeries> channels = simulate_static_channels(grade, hours, rate_hz, 5000u + seed);
    AnalysisOptions auto_opt, gm_opt;
    gm_opt.fit_options.gauss_markov = true;
    gm_opt.fit_options.choose_bias_model = false;
    const auto by_default = analyze(channels, auto_opt);
    const auto forced = analyze(channels, gm_opt);
    for (size_t c = 0; c < channels.size(); ++c) {
      tally(s.by_default[c], by_default[c]);
      tally(s.gauss_markov[c], forced[c]);
    }
    std::fprintf(stderr, "%s seed %d of %d done\n", grade_name.c_str(), seed - first_seed + 1, seeds);
  }
  return s;
}

inline void print_study(const PaperStudy& s, const char* label, const std::vector<AxisTally>& axes) {
  std::printf("== %s, %s: term  within-tolerance / covered by 95%% interval / judged  (RMS error, Cramer-Rao)\n",
              s.grade.c_str(), label);
  for (const AxisTally& a : axes) {
    std::printf("%-8s GM chosen %2d/%2d |", a.truth.channel.c_str(), a.gm_chosen, a.seeds);
    for (int i = 0; i < static_cast<int>(PaperTerm::kCount); ++i) {
      const auto t = static_cast<PaperTerm>(i);
      const TermTally& tt = a[t];
      if (a.truth[t] > 0)
        std::printf(" %s %d/%d/%d (%.1f%%, bound %.1f%%) |", term_name(t), tt.within, tt.covered, tt.judged,
                    100 * tt.rms(), 100 * tt.precision());
      else if (tt.absent_judged)
        std::printf(" %s absent, resolved %d |", term_name(t), tt.resolved_absent);
    }
    std::printf("\n");
  }
}

// P(X <= k), X ~ Binomial(n, p): how often an interval that holds the truth with probability p does this badly
// or worse in n seeds (a calibrated 95 % interval is inside in 17 or fewer of 20 in 7.5 % of sets).
inline double binomial_lower_tail(int k, int n, double p) {
  double tail = 0.0;
  for (int i = 0; i <= k; ++i)
    tail += std::exp(std::lgamma(n + 1.0) - std::lgamma(i + 1.0) - std::lgamma(n - i + 1.0) + i * std::log(p) +
                     (n - i) * std::log1p(-p));
  return std::min(1.0, tail);
}

// Calibration of the 95 % intervals over every term, axis and seed of one analysis: a few hundred intervals,
// where one tally of 20 cannot tell a calibrated interval from a narrow one. Under calibration the pooled share is
// 95 %, with a standard error of 1 % for 500 independent intervals and more since the terms of one record miss
// together: below 92 % the intervals are too narrow; above 99 % too wide (a cut-off widened until every tally
// of 20 passes would get there).
constexpr double kPooledCoverageMin = 0.92, kPooledCoverageMax = 0.99;

// Calls f(axis, term, its tally, "GRADE LABEL CHANNEL TERM") for every term of every axis of one analysis.
template <class F>
void for_each_term(const PaperStudy& s, const std::vector<AxisTally>& axes, const char* label, F f) {
  for (const AxisTally& a : axes)
    for (int i = 0; i < static_cast<int>(PaperTerm::kCount); ++i) {
      const auto t = static_cast<PaperTerm>(i);
      f(a, t, a[t], s.grade + " " + label + " " + a.truth.channel + " " + term_name(t));
    }
}

inline void print_beyond_the_record(const std::string& what, const TermTally& tt, PaperTerm t) {
  std::printf("%s: beyond the record (bound %.1f %% x 1.645 > %.0f %%): within in %d of %d, RMS %.1f %%\n",
              what.c_str(), 100 * tt.precision(), 100 * tolerance(t), tt.within, tt.judged, 100 * tt.rms());
}

// The issue's criteria on one analysis of a study: absent terms never resolved; every term carried inside its
// reported 95 % interval in `fraction` of the seeds; within its tolerance in `fraction` of the seeds where the
// record's information allows it (1.645 x bound <= tolerance), else printed as beyond the record.
inline void expect_paper_criteria(const PaperStudy& s, const std::vector<AxisTally>& axes, const char* label,
                                  double fraction) {
  for_each_term(s, axes, label, [&](const AxisTally& a, PaperTerm t, const TermTally& tt, const std::string& what) {
    if (a.truth[t] <= 0) {
      EXPECT_EQ(tt.resolved_absent, 0) << what << ": absent in the paper's table, reported resolved";
      return;
    }
    if (tt.judged == 0) return;  // the flat B was chosen every time: no GM to judge
    const double need = fraction * tt.judged;
    EXPECT_GE(tt.covered, need) << what << ": truth inside the 95 % interval in " << tt.covered << " of " << tt.judged
                                << " (a calibrated interval does this or worse in "
                                << std::round(1000 * binomial_lower_tail(tt.covered, tt.judged, 0.95)) / 10
                                << " % of sets)";
    if (reachable(tt, t))
      EXPECT_GE(tt.within, need) << what << ": within " << 100 * tolerance(t) << " % in " << tt.within << " of "
                                 << tt.judged << " (RMS " << 100 * tt.rms() << " %, bound " << 100 * tt.precision()
                                 << " %)";
    else
      print_beyond_the_record(what, tt, t);
  });
}

// The issue's per-term bars at 20 seeds, judged as what they can tell. "Inside the 95 % interval in 90 % of
// seeds" is missed by a calibrated interval in 7.5 % of tallies of 20 (17 of 20 or fewer), and a study judges
// about 200: some 16 miss it by chance alone, so a test that asserts the bar tally by tally fails on a perfect
// estimator. A tally fails here when it misses the bar by more than chance: under 90 % of seeds, and a count a
// calibrated interval reaches in fewer than kTallyTailMin of sets (14 of 20 or fewer; under 0.1 such tallies
// expected over the study). Within tolerance (where the record's bound allows it) likewise: under 90 %, and a count
// an efficient unbiased estimator (normal, relative sigma the Cramer-Rao bound) reaches in fewer than
// kTallyTailMin of sets. Never stricter than the bar: a tally at 90 % or more passes. Calibration proper is the
// pooled test below, where a few hundred intervals give it power. Terms the paper did not identify: a call is a
// false alarm of a significance test, so the study's calls must not exceed what a two-sided 3-sigma test makes
// (0.27 % of records) by more than kTallyTailMin's chance; each call is printed. Every tally under the bar is
// printed with its tail, and their count against the number a calibrated interval expects.
constexpr double kTallyTailMin = 0.001;
constexpr double kAbsentFalseAlarm = 0.0027;

inline double efficient_within_share(double tolerance_rel, double bound_rel) {
  return std::erf(tolerance_rel / (bound_rel * std::sqrt(2.0)));
}

// P(X >= k), X ~ Binomial(n, p).
inline double binomial_upper_tail(int k, int n, double p) {
  return k <= 0 ? 1.0 : 1.0 - binomial_lower_tail(k - 1, n, p);
}

inline void expect_paper_criteria_tested(const PaperStudy& s, const std::vector<AxisTally>& axes, const char* label) {
  int under_bar = 0, tallies = 0, absent_calls = 0, absent_records = 0;
  double expected_under_bar = 0.0;
  for_each_term(s, axes, label, [&](const AxisTally& a, PaperTerm t, const TermTally& tt, const std::string& what) {
    if (a.truth[t] <= 0) {
      absent_calls += tt.resolved_absent, absent_records += tt.absent_judged;
      if (tt.resolved_absent > 0)
        std::printf("%s: absent in the paper's table, reported resolved in %d of %d seeds\n", what.c_str(),
                    tt.resolved_absent, tt.absent_judged);
      return;
    }
    if (tt.judged == 0) return;  // the flat B was chosen every time: no GM to judge
    const int bar = static_cast<int>(std::ceil(0.9 * tt.judged - 1e-9));
    ++tallies;
    expected_under_bar += binomial_lower_tail(bar - 1, tt.judged, 0.95);
    const double covered_tail = binomial_lower_tail(tt.covered, tt.judged, 0.95);
    if (tt.covered < bar) {
      ++under_bar;
      std::printf(
          "%s: under the 90 %% bar, truth inside the 95 %% interval in %d of %d (a calibrated interval "
          "does this or worse in %.1f %% of sets)\n",
          what.c_str(), tt.covered, tt.judged, 100 * covered_tail);
      EXPECT_GE(covered_tail, kTallyTailMin) << what << ": truth inside the 95 % interval in only " << tt.covered
                                             << " of " << tt.judged << ": the interval is too narrow";
    }
    if (!reachable(tt, t)) {
      print_beyond_the_record(what, tt, t);
      return;
    }
    if (tt.within >= bar) return;
    const double share = efficient_within_share(tolerance(t), tt.precision());
    const double within_tail = binomial_lower_tail(tt.within, tt.judged, share);
    std::printf(
        "%s: under the 90 %% bar, within %.0f %% in %d of %d (RMS %.1f %%, bound %.1f %%: an efficient "
        "estimator is within in %.1f %% of seeds, and does this or worse in %.1f %% of sets)\n",
        what.c_str(), 100 * tolerance(t), tt.within, tt.judged, 100 * tt.rms(), 100 * tt.precision(), 100 * share,
        100 * within_tail);
    EXPECT_GE(within_tail, kTallyTailMin)
        << what << ": within " << 100 * tolerance(t) << " % in only " << tt.within << " of " << tt.judged << " (RMS "
        << 100 * tt.rms() << " %, bound " << 100 * tt.precision() << " %)";
  });
  std::printf("%s %s: %d of %d interval tallies under the 90 %% bar; a calibrated interval expects %.1f\n",
              s.grade.c_str(), label, under_bar, tallies, expected_under_bar);
  const double absent_tail = binomial_upper_tail(absent_calls, absent_records, kAbsentFalseAlarm);
  std::printf(
      "%s %s: absent terms reported resolved in %d of %d records (a 3-sigma test calls %.2f; this many or "
      "more in %.1f %% of studies)\n",
      s.grade.c_str(), label, absent_calls, absent_records, kAbsentFalseAlarm * absent_records, 100 * absent_tail);
  EXPECT_GE(absent_tail, kTallyTailMin) << s.grade << " " << label << ": absent terms called resolved " << absent_calls
                                        << " times in " << absent_records << " records";
}

// The pooled coverage (kPooledCoverageMin/Max) of one analysis of a study.
inline void expect_pooled_coverage_calibrated(const PaperStudy& s, const std::vector<AxisTally>& axes,
                                              const char* label) {
  int pooled_covered = 0, pooled_judged = 0;
  for_each_term(s, axes, label, [&](const AxisTally& a, PaperTerm t, const TermTally& tt, const std::string&) {
    if (a.truth[t] > 0) pooled_covered += tt.covered, pooled_judged += tt.judged;
  });
  ASSERT_GT(pooled_judged, 0);
  const double pooled = static_cast<double>(pooled_covered) / pooled_judged;
  std::printf("%s %s: every interval pooled, truth inside in %d of %d (%.1f %%)\n", s.grade.c_str(), label,
              pooled_covered, pooled_judged, 100 * pooled);
  EXPECT_GE(pooled, kPooledCoverageMin) << s.grade << " " << label << ": intervals too narrow, truth inside in "
                                        << pooled_covered << " of " << pooled_judged;
  EXPECT_LE(pooled, kPooledCoverageMax) << s.grade << " " << label << ": intervals too wide, truth inside in "
                                        << pooled_covered << " of " << pooled_judged;
}

}  // namespace ldv::allan::test
