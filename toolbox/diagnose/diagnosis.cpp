#include "toolbox/diagnose/diagnosis.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "common/io/input_error.hpp"
#include "estimator/calibrate/installed_imu_noise.hpp"
#include "estimator/filter/nav_filter.hpp"
#include "estimator/run/run_navigation.hpp"
#include "toolbox/diagnose/filter_run.hpp"
#include "toolbox/diagnose/noise_candidate.hpp"

namespace ldv::diag {
namespace {

std::vector<CandidateScore> final_ranking(const DiagnosisStep& first) {
  std::vector<const Confirmation*> confirmed;
  for (const Confirmation& c : first.confirmations) confirmed.push_back(&c);
  std::stable_sort(confirmed.begin(), confirmed.end(), [](const Confirmation* a, const Confirmation* b) {
    if (a->accepted != b->accepted) return a->accepted;
    return a->adjusted_gain - a->penalty > b->adjusted_gain - b->penalty;
  });
  std::vector<CandidateScore> out;
  for (const Confirmation* c : confirmed)
    for (const CandidateScore& cs : first.screening.ranked)
      if (cs.name == c->effect) out.push_back(cs);
  for (const CandidateScore& cs : first.screening.ranked)
    if (std::none_of(confirmed.begin(), confirmed.end(), [&](const Confirmation* c) { return c->effect == cs.name; }))
      out.push_back(cs);
  return out;
}

std::vector<Segment> record_segments(const FilterRun& run, const std::vector<Segment>& labels) {
  std::vector<Segment> out;
  out.reserve(run.records.size());
  for (const auto& r : run.records) out.push_back(segment_at(run.epochs, labels, r.t_s));
  return out;
}

// The long-run factor and effective sample size used to deflate likelihood gains.
void innovation_scale(const ModelCheck& mc, double& long_run_factor, double& effective_n) {
  long_run_factor = 1.0;
  effective_n = 0.0;
  for (const SensorCheck& s : mc.sensors) {
    long_run_factor = std::max(long_run_factor, s.long_run_factor);
    effective_n += s.effective_n;
  }
}

double rejected_fraction(const FilterRun& run) {
  if (run.records.empty()) return 0.0;
  long rejected = 0;
  for (const auto& r : run.records) rejected += !r.used;
  return static_cast<double>(rejected) / run.records.size();
}

constexpr double kOpenGateProbability = 1.0 - 1e-12;  // NIS gate ~ 60: only numerical garbage rejected

}  // namespace

// The model as it ends (with what was added) passes its check, and the last step found nothing more to add.
bool Diagnosis::self_calibration_applied() const {
  return std::any_of(self_calibration.begin(), self_calibration.end(), [](const SelfCalibration& c) { return c.applied; });
}

bool Diagnosis::consistent() const {
  return !steps.empty() && steps.back().added.empty() && steps.back().check.consistent();
}

namespace {

// The IMU noise as installed, from a GNSS standstill in the data (installed_imu_noise.hpp); above
// kApplyImuNoiseScale the model takes it (each sensor's white-noise density scaled by the square root of its
// PSD factor). Not from the filter's in-flight adaptation: that absorbs every missing effect (a lever arm,
// a time offset) into noise and would hide what the diagnosis is looking for.
void measure_imu_noise(const DiagnoseInputs& in, est::FilterOptions& model, Diagnosis& d) {
  const est::InstalledImuNoise noise = est::measure_installed_imu_noise(in.imu, in.gnss);
  d.imu_noise_scale = noise.psd_scale(model.arw_rad_per_sqrt_s, model.vrw_mps_per_sqrt_s);
  if (noise.found) {
    d.imu_noise_measured = noise.psd_scale_unbounded(model.arw_rad_per_sqrt_s, model.vrw_mps_per_sqrt_s);
    d.imu_noise_measured_sigma = noise.psd_scale_sigma(model.arw_rad_per_sqrt_s, model.vrw_mps_per_sqrt_s);
  }
  d.imu_noise_standstill_s = noise.found ? noise.standstill_s : 0.0;
  if (d.imu_noise_scale.larger() < kApplyImuNoiseScale) return;
  const FilterRun configured = run_filter(in, model, nullptr);
  ++d.filter_runs;
  d.configured_check = check_model(configured, classify_epochs(configured.epochs));
  model.arw_rad_per_sqrt_s *= std::sqrt(d.imu_noise_scale.gyro);
  model.vrw_mps_per_sqrt_s *= std::sqrt(d.imu_noise_scale.accel);
  d.imu_noise_applied = true;
}

// The noise as installed and the turn-on gyro bias the start took out: estimated by the system, not by the model.
void add_self_calibration_findings(Diagnosis& d) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (d.imu_noise_added) {
    // What the model now runs with, on the configured PSD: the standstill's (where applied) times the innovations'.
    const EffectEstimate& e = *d.imu_noise_added;
    const Eigen::Vector2d standstill = d.imu_noise_applied
                                           ? Eigen::Vector2d(d.imu_noise_scale.gyro, d.imu_noise_scale.accel)
                                           : Eigen::Vector2d::Ones();
    SelfCalibration c;
    c.name = "imu_noise";
    c.estimate_si = e.value_si.cwiseProduct(standstill);
    c.sigma_si = e.std_si.cwiseProduct(standstill);
    c.unit = "x the configured PSD (gyro, accel)";
    c.applied = true;
    char b[320];
    std::snprintf(b, sizeof b,
                  "the GNSS position innovations called for %.3g x (gyro) and %.3g x (accel) the PSD the diagnosis ran "
                  "with%s; its rerun fit the fixes best of the candidates: taken in",
                  e.value_si(0), e.value_si(1), d.imu_noise_applied ? " (the standstill's measurement)" : "");
    c.note = b;
    d.self_calibration.push_back(c);
  } else if (d.imu_noise_standstill_s > 0.0) {
    SelfCalibration c;
    c.name = "imu_noise";
    c.estimate_si = Eigen::Vector2d(d.imu_noise_measured.gyro, d.imu_noise_measured.accel);
    c.sigma_si = Eigen::Vector2d(d.imu_noise_measured_sigma.gyro, d.imu_noise_measured_sigma.accel);
    c.unit = "x the configured PSD (gyro, accel)";
    c.applied = d.imu_noise_applied;
    char b[160];
    std::snprintf(b, sizeof b, "white noise measured over a %.0f s GNSS standstill; %s", d.imu_noise_standstill_s,
                  c.applied ? "the diagnosis ran with it" : "within the configuration's, not applied");
    c.note = b;
    d.self_calibration.push_back(c);
  }
  {
    std::vector<double> factors, sigmas;
    std::string classes;
    for (int c = 0; c < est::NoiseAdaptation::kGnssClasses; ++c)
      if (d.gnss_noise.gnss_fixes(c) > 0) {
        factors.push_back(d.gnss_noise.gnss_scale(c));
        sigmas.push_back(d.gnss_noise.gnss_scale_sigma(c));
        classes += std::string(classes.empty() ? "" : ", ") + est::NoiseAdaptation::gnss_class_name(c);
      }
    if (!factors.empty()) {
      SelfCalibration c;
      c.name = "gnss_noise";
      c.estimate_si = Eigen::Map<const Eigen::VectorXd>(factors.data(), static_cast<Eigen::Index>(factors.size()));
      c.sigma_si = Eigen::Map<const Eigen::VectorXd>(sigmas.data(), static_cast<Eigen::Index>(sigmas.size()));
      c.unit = "x the stated position variance (" + classes + ")";
      c.applied = d.gnss_noise_added.has_value();
      const bool rerun = std::any_of(d.steps.begin(), d.steps.end(), [](const DiagnosisStep& st) {
        return std::any_of(st.confirmations.begin(), st.confirmations.end(),
                           [](const Confirmation& k) { return k.effect == kGnssNoiseCandidate; });
      });
      c.note =
          std::string("from the GNSS position innovations, apart from the IMU's noise (fix-to-fix differences); ") +
          (d.gnss_noise_added ? "its rerun fit the fixes best of the candidates: taken in (ldv.gnss_variance_scale)"
           : rerun            ? "its rerun did not fit the fixes better than the candidates: not taken in"
                              : "within 2 sigma of the stated: the configured model kept");
      d.self_calibration.push_back(c);
    }
  }
  const Vec3 seed = d.before.summary.gyro_bias_seed_rad_s;
  if (!seed.isZero()) {
    SelfCalibration c;
    c.name = "gyro_bias";
    c.estimate_si = seed;
    const Vec3& seed_std = d.before.summary.gyro_bias_seed_std_rad_s;
    c.sigma_si = seed_std.isZero() ? Vec3::Constant(nan) : seed_std;
    c.unit = "deg/h";
    c.print_scale = kRadToDeg * 3600.0;
    c.applied = true;
    c.note = "turn-on bias measured over the start's static window and taken out of every sample";
    d.self_calibration.push_back(c);
  }
  // The body heading of an unknown mounting, chosen among ldv.align_hypotheses at the start (nav_session.cpp).
  if (const auto& h = d.before.summary.body_heading) {
    SelfCalibration c;
    c.name = "body_heading";
    c.estimate_si = Eigen::VectorXd::Constant(1, h->from_course_rad);
    c.sigma_si = Eigen::VectorXd::Constant(1, 0.5 * h->spacing_rad);  // the alignment's own heading sigma then
    c.unit = "deg";
    c.print_scale = kRadToDeg;
    c.applied = true;
    char b[200];
    std::snprintf(
        b, sizeof b, "the IMU's x axis from the GNSS course at the start, best of %d headings %s", h->tried,
        h->by_accelerations ? "by the accelerations against the track" : "by a filter's innovations per heading");
    c.note = b;
    d.self_calibration.push_back(c);
  }
}

}  // namespace

namespace {
// No result on no data (issue 46: 0 measurement epochs were reported as "the model is consistent with the data"):
// the diagnosis refuses, saying where the measurements and the IMU lie in time.
[[noreturn]] void throw_no_measurements(const DiagnoseInputs& in) {
  char b[400];
  const double imu0 = in.imu.empty() ? NAN : in.imu.front().t_s, imu1 = in.imu.empty() ? NAN : in.imu.back().t_s;
  if (in.gnss.empty())
    std::snprintf(b, sizeof b,
                  "no measurement reached the filter (no GNSS fix; IMU %.3f to %.3f s, no standstill): "
                  "nothing to diagnose",
                  imu0, imu1);
  else
    std::snprintf(b, sizeof b,
                  "no measurement reached the filter: %zu GNSS fixes from %.3f to %.3f s, the IMU from "
                  "%.3f to %.3f s (do their times overlap, on one time scale?): nothing to diagnose",
                  in.gnss.size(), in.gnss.front().t_s, in.gnss.back().t_s, imu0, imu1);
  throw InputError(in.cfg.gnss_path.empty() ? std::string("GNSS") : in.cfg.gnss_path, 0, b);
}
}  // namespace

Diagnosis diagnose(const DiagnoseInputs& in, const DiagnoseOptions& opt) {
  if (opt.max_added < 0) throw std::invalid_argument("diagnose: max_added must be >= 0, got " + std::to_string(opt.max_added));
  const double cpu0 = process_cpu_seconds();
  Diagnosis d;
  d.model = opt.model.model;
  est::FilterOptions current = opt.model;
  current.adapt_imu_noise = false;  // the model check judges the model as configured
  if (opt.measure_imu_noise) measure_imu_noise(in, current, d);
  std::optional<MeasuredNoise> first_noise;
  if (opt.measure_imu_noise)
    if ((first_noise = measure_noise(in, current))) {
      d.gnss_noise = first_noise->adaptation;
      ++d.filter_runs;
    }
  FilterRun current_run;
  for (int step = 0; step <= opt.max_added; ++step) {
    DiagnosisStep st;
    st.model_effects = est::resolve_model(current.model, current.add, current.drop);
    if (step == 0) d.model_effects = st.model_effects;
    st.candidates = make_candidates(current, st.model_effects);
    if (opt.verbose) std::fprintf(stderr, "ldv diagnose: screening run %d (%zu candidates)\n", step + 1, st.candidates.candidates.size());
    current_run = run_filter(in, current, &st.candidates);
    ++d.filter_runs;
    if (step == 0 && rejected_fraction(current_run) > opt.open_gate_above_rejected) {
      if (opt.verbose) std::fprintf(stderr, "ldv diagnose: %.0f %% of the measurements rejected: gate opened\n", 100.0 * rejected_fraction(current_run));
      current.gate_probability = kOpenGateProbability;
      d.gate_opened = true;
      current_run = run_filter(in, current, &st.candidates);
      ++d.filter_runs;
    }
    if (step == 0 && current_run.records.empty()) throw_no_measurements(in);
    const std::vector<Segment> labels = classify_epochs(current_run.epochs);
    st.check = check_model(current_run, labels);
    st.screening = screen(st.candidates, current_run.records, record_segments(current_run, labels), opt.screening);
    if (step == 0) {
      d.before = current_run;
      d.labels_before = labels;
    }
    double lrf, n_eff;
    innovation_scale(st.check, lrf, n_eff);
    const Confirmation* best = nullptr;
    if (step < opt.max_added) {
      int tried = 0;
      for (const CandidateScore& cs : st.screening.ranked) {
        if (!cs.significant || (opt.max_confirmed_per_step >= 0 && tried >= opt.max_confirmed_per_step)) continue;
        ++tried;
        if (opt.verbose) std::fprintf(stderr, "ldv diagnose: confirming %s\n", cs.name.c_str());
        st.confirmations.push_back(confirm(in, current, current_run, cs, lrf, n_eff));
        ++d.filter_runs;
      }
      // The score test is a linearisation at the model under test. So far from the data that the gate rejects
      // fixes, the states absorb a large missing effect's signal and the gate drops the fixes that carry it: a
      // van's 4.9 m lever arm on a MEMS drive scored p = 0.12 while its rerun gained 8826 in log-likelihood
      // (issue 48, item 4). Then every testable candidate is confirmed by its rerun, and the likelihood decides.
      if (opt.confirm_all_when_gate_rejects && st.check.gate_drops_fixes())
        for (const CandidateScore& cs : st.screening.ranked) {
          if (!cs.testable || std::any_of(st.confirmations.begin(), st.confirmations.end(),
                                          [&](const Confirmation& c) { return c.effect == cs.name; }))
            continue;
          if (opt.verbose)
            std::fprintf(stderr, "ldv diagnose: confirming %s (the gate drops fixes)\n", cs.name.c_str());
          st.confirmations.push_back(confirm(in, current, current_run, cs, lrf, n_eff));
          ++d.filter_runs;
        }
      // The GNSS and the IMU noise compete on the same likelihood (effects before noise: a noise goes first only
      // where it explains the fixes better than every effect does).
      if (opt.measure_imu_noise && !(d.gnss_noise_added && d.imu_noise_added)) {
        const std::optional<MeasuredNoise> measured = step == 0 ? first_noise : measure_noise(in, current);
        d.filter_runs += step > 0;
        std::optional<Confirmation> gnss, imu;
        if (measured && !d.gnss_noise_added)
          gnss = confirm_gnss_noise(in, current, current_run, measured->adaptation, lrf, n_eff);
        if (measured && !d.imu_noise_added) imu = confirm_imu_noise(in, current, current_run, *measured, lrf, n_eff);
        for (std::optional<Confirmation>* c : {&gnss, &imu})
          if (*c) {
            if (opt.verbose) std::fprintf(stderr, "ldv diagnose: confirming %s\n", (*c)->effect.c_str());
            d.filter_runs += (*c)->filter_runs;
            st.confirmations.push_back(std::move(**c));
          }
      }
      for (const Confirmation& c : st.confirmations)
        if (c.accepted && (!best || c.adjusted_gain - c.penalty > best->adjusted_gain - best->penalty)) best = &c;
    }
    if (best) {
      st.added = best->effect;
      if (best->effect == kGnssNoiseCandidate) {
        d.gnss_noise_added = best->estimate;
      } else if (best->effect == kImuNoiseCandidate) {
        d.imu_noise_added = best->estimate;
      } else {
        d.add.push_back(best->effect);
      }
      current = best->options;
      d.after = best->run;
    }
    d.steps.push_back(std::move(st));
    if (!best) break;
  }
  d.ranking = final_ranking(d.steps.front());
  d.final_options = current;
  if (!d.changed()) d.after = d.before;
  for (const std::string& name : d.add)
    for (const EffectEstimate& e : d.after.estimates)
      if (e.name == name) d.added_estimates.push_back(e);
  if (!d.add.empty()) {
    // "After" is the tuned model as --write-config states it and `ldv nav` runs it (issue 48, item 1): each added
    // effect starts from its estimate with its sigma as the prior. The estimates reported stay the last step's
    // (the tuned run's own would count the drive twice).
    for (const EffectEstimate& e : d.added_estimates)
      if (e.value_si.allFinite() && e.std_si.allFinite()) set_prior(current, e.name, e.value_si, e.std_si);
    d.after = run_filter(in, current);
    ++d.filter_runs;
    d.final_options = current;
  }
  d.labels_after = classify_epochs(d.after.epochs);
  d.check_after = d.changed() ? d.steps.back().check : d.steps.front().check;
  d.truth_before = truth_error(d.before, d.labels_before, in.truth, opt.truth_skip_s);
  d.truth_after = truth_error(d.after, d.labels_after, in.truth, opt.truth_skip_s);
  add_self_calibration_findings(d);
  d.cpu_s = process_cpu_seconds() - cpu0;
  return d;
}

std::string config_snippet(const Diagnosis& d) {
  std::ostringstream s;
  s << "ldv:\n  model: " << d.model << "\n  add: [";
  for (size_t i = 0; i < d.add.size(); ++i) s << (i ? ", " : "") << d.add[i];
  s << "]\n";
  for (const EffectEstimate& e : d.added_estimates) {
    s << "  # " << e.name << " estimated [" << e.unit.unit << "]:";
    for (int i = 0; i < e.value_si.size(); ++i) s << " " << e.value_si(i) * e.unit.scale;
    s << "  (1-sigma";
    for (int i = 0; i < e.std_si.size(); ++i) s << " " << e.std_si(i) * e.unit.scale;
    s << ")\n";
  }
  if (d.imu_noise_added) {
    const EffectEstimate& e = *d.imu_noise_added;
    s << "  # imu_noise: imunoise.arw times " << std::sqrt(e.value_si(0)) << ", imunoise.vrw times "
      << std::sqrt(e.value_si(1)) << " (the PSDs times " << e.value_si(0) << ", " << e.value_si(1) << ")\n";
  }
  if (d.gnss_noise_added) {
    const auto& k = d.final_options.gnss_variance_scale;
    s << "  gnss_variance_scale: [" << k[0] << ", " << k[1] << ", " << k[2]
      << "]   # the stated GNSS position variance times these: fixed, float, other\n";
  }
  for (const EffectEstimate& e : d.added_estimates)
    if (e.name == "lever_arm")
      s << "antlever: [" << e.value_si(0) << ", " << e.value_si(1) << ", " << e.value_si(2) << "]   # m, front-right-down\n";
  return s.str();
}

}  // namespace ldv::diag
