#include "toolbox/diagnose/report_text.hpp"

#include <cmath>
#include <cstdio>
#include <ostream>
#include <string>

namespace ldv::diag {
namespace {

std::string fmt(const char* f, double v) {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

std::string values(const Eigen::VectorXd& v, double scale) {
  std::string s;
  for (int i = 0; i < v.size(); ++i) s += (i ? " " : "") + (std::isfinite(v(i)) ? fmt("%.4g", v(i) * scale) : std::string("-"));
  return s;
}

std::string rms_text(const Eigen::VectorXd& rms) {
  std::string t;
  for (int i = 0; i < rms.size(); ++i) t += (i ? " " : "") + fmt("%.4f", rms(i));
  return t;
}

void print_check(std::ostream& out, const ModelCheck& mc) {
  for (const SensorCheck& s : mc.sensors) {
    out << "  " << std::string(s.sensor) << ": " << s.count << " measurements, " << s.rejected
        << " gate rejections; mean NIS " << fmt("%.2f", s.mean_nis.value) << " (band " << fmt("%.2f", s.mean_nis.lo)
        << ".." << fmt("%.2f", s.mean_nis.hi) << ") "
        << (s.optimistic()    ? "TOO HIGH (errors larger than the model says)"
            : s.pessimistic() ? "low (the model is pessimistic: noise larger than needed)"
                              : "ok")
        << "\n";
    out << "    per row" << (s.axis_nis.size() == 3 && s.sensor.starts_with("gnss") ? " N E D" : "") << ":";
    for (const Band& b : s.axis_nis) out << " " << fmt("%.2f", b.value);
    out << "; RMS";
    for (int i = 0; i < s.rms.size(); ++i) out << " " << fmt("%.4f", s.rms(i));
    out << "\n";
    out << "    whiteness: lag-1 autocorrelation " << fmt("%.2f", s.autocorrelation.size() > 1 ? s.autocorrelation[1] : 0.0)
        << ", Ljung-Box(" << s.ljung_box_lags << ") " << fmt("%.1f", s.ljung_box) << " p=" << fmt("%.2g", s.ljung_box_p)
        << ", correlation time " << fmt("%.1f", s.correlation_time) << " measurements, effective N "
        << fmt("%.0f", s.effective_n) << "\n";
    for (const SegmentCheck& g : s.segments)
      out << "    " << segment_name(g.segment) << std::string(14 - std::string(segment_name(g.segment)).size(), ' ')
          << fmt("%5.0f", g.count) << "  mean NIS " << fmt("%7.2f", g.mean_nis.value)
          << (g.mean_nis.ok() ? "   " : " ! ") << " RMS " << rms_text(g.rms)
          << (g.rejected ? "  rejected " + std::to_string(g.rejected) : std::string()) << "\n";
  }
}

void print_screening(std::ostream& out, const ScreeningResult& s) {
  out << "  " << s.epochs << " measurement epochs, Newey-West bandwidth " << s.bandwidth_epochs << " epochs (dof "
      << fmt("%.0f", s.nu_eff) << "), threshold p < " << fmt("%.2g", s.threshold_p) << "\n";
  out << "  rank effect               dof  statistic   p-value   estimate +- sigma [unit]   (min detectable)\n";
  int rank = 0;
  for (const CandidateScore& c : s.ranked) {
    ++rank;
    if (!c.testable) {
      out << "   -   " << c.name << std::string(21 - c.name.size(), ' ')
          << "untestable on this drive (too little information)\n";
      continue;
    }
    out << "  " << fmt("%3.0f", rank) << "  " << c.name << std::string(21 - c.name.size(), ' ') << fmt("%3.0f", c.tested.size())
        << fmt("%11.1f", c.statistic) << fmt("%10.2g", c.p_value) << (c.significant ? " * " : "   ") << "["
        << values(c.estimate_si, c.unit.scale) << "] +- [" << values(c.sigma_si, c.unit.scale) << "] " << c.unit.unit
        << "  (" << values(c.mds_si, c.unit.scale) << ")\n";
    if (c.group.size() > 1) {
      out << "        group (cannot be told apart here):";
      for (const auto& g : c.group) out << " " << g;
      out << "\n        to separate: " << c.separate_by << "\n";
    }
  }
}

void print_truth(std::ostream& out, const char* label, const TruthError& t) {
  if (!t.available) return;
  out << "  " << label << " position error RMS 3D " << fmt("%.3f", t.rms_pos_3d_m) << " m (horizontal "
      << fmt("%.3f", t.rms_horizontal_m) << ", vertical " << fmt("%.3f", t.rms_vertical_m) << ", max horizontal "
      << fmt("%.3f", t.max_horizontal_m) << "), yaw RMS " << fmt("%.3f", t.rms_yaw_deg) << " deg\n";
}

// Why nothing is added, in words that do not claim more than the data showed: "consistent" only when
// the model check passed and no candidate was significant.
std::string why_nothing(const Diagnosis& d) {
  const DiagnosisStep& first = d.steps.front();
  std::string significant;
  for (const CandidateScore& c : first.screening.ranked) {
    if (!c.significant) continue;
    significant += (significant.empty() ? "" : ", ") + c.name;
    if (c.group.size() > 1) {
      significant += " (cannot be told apart here from";
      for (const auto& g : c.group)
        if (g != c.name) significant += " " + g;
      significant += "; to separate: " + c.separate_by + ")";
    }
  }
  if (!significant.empty())
    return ": significant in the screening but not confirmed by the reruns: " + significant +
           ". The data do not settle it; the model is NOT shown consistent";
  if (!first.check.consistent())
    return ": the model does not fit the measurements (see the model check) and no candidate effect explains it; "
           "look at the noise model and the untested effects";
  if (d.self_calibration_applied()) {
    std::string what;
    for (const SelfCalibration& c : d.self_calibration)
      if (c.applied) what += (what.empty() ? "" : ", ") + c.name;
    return " (the model is consistent with the data once the system's own calibration took out " + what +
           ": see Self-calibration above)";
  }
  return " (the model is consistent with the data)";
}

// The GNSS noise a step took in, in words: "rescale the GNSS noise: the stated position variance of fixed solutions
// times 12.1 (std times 3.48)".
std::string gnss_noise_words(const EffectEstimate& e) {
  std::string words = "rescale the GNSS noise: the stated position variance of";
  for (int i = 0; i < e.value_si.size(); ++i)
    words += std::string(i ? "," : "") + " " + e.state_names[static_cast<size_t>(i)] + " solutions times " +
             fmt("%.3g", e.value_si(i)) + " (std times " + fmt("%.3g", std::sqrt(e.value_si(i))) + ")";
  return words;
}

// What the system estimated on its own (ldv diagnose's findings beside the model's): value, sigma, applied.
void print_self_calibration(std::ostream& out, const Diagnosis& d) {
  if (d.self_calibration.empty()) return;
  out << "  Self-calibration (estimated by the system on its own, outside the model under test):\n";
  for (const SelfCalibration& c : d.self_calibration) {
    out << "    " << c.name << " = [" << values(c.estimate_si, c.print_scale) << "]";
    if (c.sigma_si.allFinite()) out << " +- [" << values(c.sigma_si, c.print_scale) << "]";
    out << " " << c.unit << (c.applied ? ", applied" : ", not applied") << ": " << c.note << "\n";
  }
}

// The error falling step by step: what each step added, its estimate, and how the model then fits.
void print_steps(std::ostream& out, const Diagnosis& d) {
  out << "\n5. Step by step (GNSS position fit of each model)\n"
      << "  step  added                 estimate +- sigma                          used / fixes  mean NIS  RMS N E D [m]\n";
  auto fit = [&](const ModelCheck& check) {
    const SensorCheck* pos = check.find(est::sensors::kGnssPosition);
    if (!pos) return std::string();
    return fmt("%5.0f", static_cast<double>(pos->count - pos->rejected)) + " / " +
           fmt("%-5.0f", static_cast<double>(pos->count)) + "  " + fmt("%8.2f", pos->mean_nis.value) + "  " +
           fmt("%.3f", pos->rms(0)) + " " + fmt("%.3f", pos->rms(1)) + " " + fmt("%.3f", pos->rms(2));
  };
  if (d.imu_noise_applied)
    out << "     -  (configured IMU noise)" << std::string(44, ' ') << fit(d.configured_check) << "\n";
  for (size_t i = 0; i < d.steps.size(); ++i) {
    std::string added = i == 0 ? (d.imu_noise_applied ? "imu_noise" : "(model under test)") : d.steps[i - 1].added, estimate;
    if (i == 0 && d.imu_noise_applied)
      estimate = "gyro x" + fmt("%.1f", d.imu_noise_scale.gyro) + ", accel x" + fmt("%.1f", d.imu_noise_scale.accel) +
                 " the configured PSD (measured)";
    if (i > 0)
      for (const Confirmation& c : d.steps[i - 1].confirmations)
        if (c.effect == added)
          estimate = "[" + values(c.estimate.value_si, c.estimate.unit.scale) + "] +- [" +
                     values(c.estimate.std_si, c.estimate.unit.scale) + "] " + c.estimate.unit.unit;
    out << "  " << fmt("%4.0f", static_cast<double>(i)) << "  " << added << std::string(added.size() < 22 ? 22 - added.size() : 1, ' ')
        << estimate << std::string(estimate.size() < 43 ? 43 - estimate.size() : 1, ' ') << fit(d.steps[i].check) << "\n";
  }
}

}  // namespace

void print_report(std::ostream& out, const Diagnosis& d) {
  out << "ldv diagnose: model " << d.model << " (";
  for (size_t i = 0; i < d.model_effects.size(); ++i) out << (i ? " " : "") << d.model_effects[i];
  out << ")\n";
  if (d.imu_noise_standstill_s > 0.0)
    out << "  IMU noise as installed (a " << fmt("%.0f", d.imu_noise_standstill_s) << " s GNSS standstill): gyro x"
        << fmt("%.1f", d.imu_noise_scale.gyro) << " (measured " << fmt("%.3g", d.imu_noise_measured.gyro) << " +- "
        << fmt("%.2g", d.imu_noise_measured_sigma.gyro) << "), accel x" << fmt("%.1f", d.imu_noise_scale.accel)
        << " (measured " << fmt("%.3g", d.imu_noise_measured.accel) << " +- "
        << fmt("%.2g", d.imu_noise_measured_sigma.accel) << ")"
        << " the configured white-noise PSD"
        << (d.imu_noise_applied ? ": the diagnosis runs with it (vibration, or a datasheet value)"
                                : ": within 2x, the configured noise kept")
        << "\n";
  print_self_calibration(out, d);
  out << "\n1. Model check\n";
  if (d.gate_opened)
    out << "  (the model rejected more than 20 % of the measurements and diverged: diagnosed with the gate opened)\n";
  print_check(out, d.steps.front().check);
  for (size_t k = 0; k < d.steps.size(); ++k) {
    const DiagnosisStep& st = d.steps[k];
    out << "\n" << (k == 0 ? "2. Screening (score test of every missing effect, one pass)" : "   Rescreening with ")
        << (k == 0 ? std::string() : d.steps[k - 1].added + " added") << "\n";
    print_screening(out, st.screening);
    if (k == 0)
      for (const NotScreened& n : st.candidates.not_screened) out << "   -   " << n.name << ": not screened, " << n.reason << "\n";
    for (const Confirmation& c : st.confirmations)
      out << "  confirm " << c.effect << ": log-likelihood gain " << fmt("%.1f", c.loglik_gain) << ", /long-run factor "
          << fmt("%.1f", c.adjusted_gain) << " vs BIC penalty " << fmt("%.1f", c.penalty) << " -> "
          << (c.accepted ? "accepted" : "rejected") << "\n";
    if (k == 0 && st.confirmations.size() > 1) {
      out << "  ranking after the reruns:";
      for (size_t i = 0; i < d.ranking.size() && i < st.confirmations.size(); ++i) out << " " << i + 1 << ". " << d.ranking[i].name;
      out << "\n";
    }
  }
  out << "\n3. Verdict: ";
  if (!d.changed()) {
    out << "nothing to add" << why_nothing(d) << "\n";
  } else {
    if (!d.add.empty()) out << "add";
    for (const auto& a : d.add) out << " " << a;
    if (d.gnss_noise_added) out << (d.add.empty() ? "" : "; ") << gnss_noise_words(*d.gnss_noise_added);
    if (d.imu_noise_added)
      out << (d.add.empty() && !d.gnss_noise_added ? "" : "; ") << "raise the IMU white noise: the PSDs times "
          << fmt("%.3g", d.imu_noise_added->value_si(0)) << " (gyro), " << fmt("%.3g", d.imu_noise_added->value_si(1))
          << " (accel)";
    out << "\n";
    for (const EffectEstimate& e : d.added_estimates)
      out << "  " << e.name << " = [" << values(e.value_si, e.unit.scale) << "] +- [" << values(e.std_si, e.unit.scale)
          << "] " << e.unit.unit << "\n";
    out << "  config snippet (KF-GINS yaml):\n";
    const std::string snip = config_snippet(d);
    size_t p = 0;
    while (p < snip.size()) {
      const size_t q = snip.find('\n', p);
      out << "    " << snip.substr(p, q - p) << "\n";
      p = q == std::string::npos ? snip.size() : q + 1;
    }
    out << "\n4. Rerun with it\n";
    print_check(out, d.check_after);
  }
  if (d.truth_before.given) {
    out << "\n   Against truth\n";
    const TruthError& t = d.truth_before;
    if (!t.available)
      out << "  not compared: " << (t.coverage_note.empty() ? "no epoch after the first seconds" : t.coverage_note)
          << "\n";
    else if (!t.coverage_note.empty())
      out << "  only part compared: " << t.coverage_note << "\n";
    print_truth(out, "before:", d.truth_before);
    if (d.changed()) {
      print_truth(out, "after: ", d.truth_after);
      out << "  (after: the tuned model, each added effect started from its estimate and sigma, as --write-config "
             "writes it and ldv nav runs it)\n";
    }
  }
  print_steps(out, d);
  out << "\n  " << d.filter_runs << " filter runs, " << fmt("%.1f", d.cpu_s) << " s CPU\n";
}

}  // namespace ldv::diag
