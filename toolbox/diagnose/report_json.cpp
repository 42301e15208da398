#include "toolbox/diagnose/report_json.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "common/io/input_error.hpp"
#include "common/io/output_file.hpp"

namespace ldv::diag {
namespace {

std::string num(double v) {
  if (!std::isfinite(v)) return "null";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

std::string str(const std::string& s) {
  std::string o = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') o += '\\';
    if (c == '\n') { o += "\\n"; continue; }
    o += c;
  }
  return o + "\"";
}

// The items of a JSON list, comma separated, without the brackets.
template <typename F>
std::string list_items(size_t n, F item) {
  std::string o;
  for (size_t i = 0; i < n; ++i) o += (i ? ", " : "") + item(i);
  return o;
}

template <typename F>
std::string list(size_t n, F item) {
  return "[" + list_items(n, item) + "]";
}

std::string vec(const Eigen::VectorXd& v) {
  return list(v.size(), [&](size_t i) { return num(v(i)); });
}

std::string names(const std::vector<std::string>& v) {
  return list(v.size(), [&](size_t i) { return str(v[i]); });
}

std::string check_json(const ModelCheck& mc) {
  return list(mc.sensors.size(), [&](size_t i) {
    const SensorCheck& s = mc.sensors[i];
    std::ostringstream o;
    o << "{\"sensor\": " << str(std::string(s.sensor)) << ", \"count\": " << s.count << ", \"rejected\": " << s.rejected
      << ", \"mean_nis\": " << num(s.mean_nis.value) << ", \"mean_nis_band\": [" << num(s.mean_nis.lo) << ", "
      << num(s.mean_nis.hi)
      << "], \"axis_nis\": " << list(s.axis_nis.size(), [&](size_t a) { return num(s.axis_nis[a].value); })
      << ", \"rms\": "
      << list(static_cast<size_t>(s.rms.size()), [&](size_t a) { return num(s.rms(static_cast<int>(a))); })
      << ", \"ljung_box\": " << num(s.ljung_box) << ", \"ljung_box_p\": " << num(s.ljung_box_p)
      << ", \"effective_n\": " << num(s.effective_n) << ", \"ok\": " << (s.ok() ? "true" : "false")
      << ", \"segments\": "
      << list(s.segments.size(),
              [&](size_t k) {
                const SegmentCheck& g = s.segments[k];
                return "{\"segment\": " + str(segment_name(g.segment)) + ", \"count\": " + std::to_string(g.count) +
                       ", \"mean_nis\": " + num(g.mean_nis.value) +
                       ", \"ok\": " + (g.mean_nis.ok() ? "true" : "false") +
                       ", \"rms\": " +
                       list(static_cast<size_t>(g.rms.size()), [&](size_t a) { return num(g.rms(static_cast<int>(a))); }) +
                       "}";
              })
      << "}";
    return o.str();
  });
}

std::string truth_json(const TruthError& t) {
  if (!t.available)
    return t.given ? "{\"compared_epochs\": 0, \"coverage_note\": " + str(t.coverage_note) + "}" : "null";
  return "{\"compared_epochs\": " + std::to_string(t.compared_epochs) +
         ", \"run_epochs\": " + std::to_string(t.run_epochs) + ", \"coverage_note\": " + str(t.coverage_note) +
         ", \"rms_pos_3d_m\": " + num(t.rms_pos_3d_m) + ", \"rms_horizontal_m\": " + num(t.rms_horizontal_m) +
         ", \"rms_vertical_m\": " + num(t.rms_vertical_m) + ", \"max_horizontal_m\": " + num(t.max_horizontal_m) +
         ", \"rms_yaw_deg\": " + num(t.rms_yaw_deg) + "}";
}

std::string candidate_json(const CandidateScore& c) {
  std::ostringstream o;
  o << "{\"effect\": " << str(c.name) << ", \"statistic\": " << num(c.statistic) << ", \"p_value\": " << num(c.p_value)
    << ", \"estimate\": " << vec(c.estimate_si) << ", \"sigma\": " << vec(c.sigma_si) << ", \"group\": " << names(c.group)
    << ", \"dof\": " << c.tested.size() << ", \"testable\": " << (c.testable ? "true" : "false")
    << ", \"significant\": " << (c.significant ? "true" : "false") << ", \"statistic_model\": " << num(c.statistic_model)
    << ", \"minimal_detectable\": " << vec(c.mds_si) << ", \"state_names\": " << names(c.state_names)
    << ", \"print_unit\": " << str(c.unit.unit) << ", \"print_scale\": " << num(c.unit.scale);
  if (!c.separate_by.empty()) o << ", \"separate_by\": " << str(c.separate_by);
  o << "}";
  return o.str();
}

// The step-by-step fall (ldv diagnose --iterate): the effect added to reach step i's model (null for the
// model under test), its estimate and sigma in that model's run (SI), and how the model then fits the
// GNSS positions.
std::string fit_json(const ModelCheck& check) {
  const SensorCheck* pos = check.find(est::sensors::kGnssPosition);
  const int total = pos ? pos->count : 0, accepted = pos ? pos->count - pos->rejected : 0;
  return "\"accepted_fixes\": " + std::to_string(accepted) + ", \"total_fixes\": " + std::to_string(total) +
         ", \"mean_nis\": " + (pos ? num(pos->mean_nis.value) : std::string("null")) +
         ", \"consistent\": " + (check.consistent() ? "true" : "false");
}

std::string step_outcome_json(const Diagnosis& d, size_t i) {
  std::string added = "null", estimate = "null", sigma = "null";
  if (i == 0 && d.imu_noise_applied) {  // the measured IMU noise took the configured one's place
    added = str("imu_noise");
    estimate = "[" + num(d.imu_noise_scale.gyro) + ", " + num(d.imu_noise_scale.accel) + "]";
  } else if (i > 0) {
    const DiagnosisStep& prev = d.steps[i - 1];
    added = str(prev.added);
    for (const Confirmation& c : prev.confirmations) {
      if (c.effect != prev.added) continue;
      estimate = vec(c.estimate.value_si);
      sigma = vec(c.estimate.std_si);
    }
  }
  return "\"added\": " + added + ", \"estimate\": " + estimate + ", \"sigma\": " + sigma + ", " +
         fit_json(d.steps[i].check);
}

}  // namespace

std::string diagnosis_json(const Diagnosis& d) {
  std::ostringstream o;
  const ScreeningResult& first = d.steps.front().screening;
  o << "{\n  \"model\": " << str(d.model) << ",\n  \"model_effects\": " << names(d.model_effects)
    << ",\n  \"consistent\": " << (d.consistent() ? "true" : "false") << ",\n  \"candidates\": [\n    ";
  for (size_t i = 0; i < d.ranking.size(); ++i) o << (i ? ",\n    " : "") << candidate_json(d.ranking[i]);
  o << "\n  ],\n  \"verdict\": {\"add\": " << names(d.add) << ", \"estimates\": "
    << list(d.added_estimates.size(),
            [&](size_t i) {
              const EffectEstimate& e = d.added_estimates[i];
              return "{\"effect\": " + str(e.name) + ", \"value\": " + vec(e.value_si) +
                     ", \"sigma\": " + vec(e.std_si) + "}";
            })
    << ", \"gnss_variance_scale\": "
    << (d.gnss_noise_added
            ? vec(Eigen::Vector3d(d.final_options.gnss_variance_scale[0], d.final_options.gnss_variance_scale[1],
                                  d.final_options.gnss_variance_scale[2]))
            : std::string("null"))
    << ", \"config_snippet\": " << str(config_snippet(d)) << "},\n";
  o << "  \"screening\": {\"epochs\": " << first.epochs << ", \"bandwidth_epochs\": " << first.bandwidth_epochs
    << ", \"nu_eff\": " << num(first.nu_eff) << ", \"threshold_p\": " << num(first.threshold_p)
    << ", \"not_screened\": "
    << list(d.steps.front().candidates.not_screened.size(), [&](size_t i) {
         const NotScreened& n = d.steps.front().candidates.not_screened[i];
         return "{\"effect\": " + str(n.name) + ", \"reason\": " + str(n.reason) + "}";
       })
    << "},\n";
  // With the measured IMU noise applied, the configured model comes first: the fall starts there.
  const std::string configured_step =
      d.imu_noise_applied ? "{\"model_effects\": " + names(d.model_effects) +
                                ", \"imu_noise\": \"configured\", \"added\": null, \"estimate\": null, \"sigma\": null, " +
                                fit_json(d.configured_check) + "},\n    "
                          : std::string();
  // What the system estimated on its own (time_offset: the IMU latency taken out; imu_noise; gyro_bias: the
  // turn-on bias): issue 36's contract, {name, estimate, sigma, applied} with the effect vocabulary's names, SI.
  o << "  \"self_calibration\": "
    << list(d.self_calibration.size(), [&](size_t i) {
         const SelfCalibration& c = d.self_calibration[i];
         return "{\"name\": " + str(c.name) + ", \"estimate\": " + vec(c.estimate_si) + ", \"sigma\": " +
                vec(c.sigma_si) + ", \"applied\": " + (c.applied ? "true" : "false") + ", \"note\": " + str(c.note) +
                "}";
       })
    << ",\n";
  o << "  \"imu_noise\": {\"psd_scale\": " << num(d.imu_noise_scale.larger())
    << ", \"gyro_psd_scale\": " << num(d.imu_noise_scale.gyro)
    << ", \"accel_psd_scale\": " << num(d.imu_noise_scale.accel)
    << ", \"applied\": " << (d.imu_noise_applied ? "true" : "false") << "},\n";
  o << "  \"steps\": [\n    " << configured_step
    << list_items(d.steps.size(), [&](size_t i) {
         const DiagnosisStep& s = d.steps[i];
         return "{\"model_effects\": " + names(s.model_effects) + ", \"top\": " +
                (s.screening.ranked.empty() ? std::string("null") : str(s.screening.ranked.front().name)) +
                ", \"confirmations\": " +
                list(s.confirmations.size(), [&](size_t k) {
                  const Confirmation& c = s.confirmations[k];
                  return "{\"effect\": " + str(c.effect) + ", \"loglik_gain\": " + num(c.loglik_gain) +
                         ", \"adjusted_gain\": " + num(c.adjusted_gain) + ", \"penalty\": " + num(c.penalty) +
                         ", \"accepted\": " + (c.accepted ? "true" : "false") + "}";
                }) +
                ", \"adds\": " + (s.added.empty() ? std::string("null") : str(s.added)) + ", " + step_outcome_json(d, i) +
                "}";
       })
    << "\n  ],\n";
  o << "  \"model_check\": {\"before\": " << check_json(d.steps.front().check) << ", \"after\": " << check_json(d.check_after)
    << "},\n";
  o << "  \"truth\": {\"before\": " << truth_json(d.truth_before) << ", \"after\": " << truth_json(d.truth_after) << "},\n";
  o << "  \"gate_opened\": " << (d.gate_opened ? "true" : "false") << ",\n";
  o << "  \"filter_runs\": " << d.filter_runs << ", \"cpu_s\": " << num(d.cpu_s) << "\n}\n";
  return o.str();
}

void write_json(const Diagnosis& d, const std::string& path) {
  std::ofstream f(path);
  if (!f) throw InputError(path, 0, "cannot open for writing");
  f << diagnosis_json(d);
  close_checked(f, path);  // a full disk shows at the flush
}

}  // namespace ldv::diag
