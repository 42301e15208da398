#pragma once
// One diagnosis trial on a simulated drive with (at most) one hidden effect, and what the tests measure:
// is the hidden effect ranked first (or in the first group), is it the verdict, and how much of the
// excess position error (above a filter that knew the true model) adding the verdict removes.
#include <algorithm>
#include <cmath>
#include <string>

#include "tests/diagnose/sim_case.hpp"

namespace ldv::diag::testing {

struct Trial {
  std::string grade = "hg1700-typical";
  std::string effect;  // spec as for `ldv sim --effect`, "" = none
  std::string model = "kfgins21";
  uint64_t seed = 1;
  double duration_s = 900.0;
  std::string scenario = "drive";
  double gnss_rate_hz = 1.0;
};

struct Outcome {
  std::string first;              // top-ranked candidate
  bool ranked_first = false;      // the hidden effect is the top candidate
  bool in_first_group = false;    // ... or in the top candidate's group
  bool verdict_has = false;       // the verdict adds the hidden effect
  bool verdict_any = false;       // the verdict adds anything
  double err_base_m = NAN, err_after_m = NAN, err_ref_m = NAN;  // RMS 3D position error vs truth
  double excess_removed() const { return (err_base_m - err_after_m) / (err_base_m - err_ref_m); }
  // The hidden effect's estimate where the verdict adds it: its largest error over its sigma, any component.
  double estimate_error_sigmas = NAN;
  double cpu_s = 0.0;
};

inline Outcome run_trial(const Trial& t, bool with_reference = false) {
  SimCase c;
  c.grade = t.grade;
  c.effect = t.effect;
  c.seed = t.seed;
  c.duration_s = t.duration_s;
  c.scenario = t.scenario;
  c.gnss_rate_hz = t.gnss_rate_hz;
  const sim::SimResult r = simulate(c);
  const DiagnoseInputs in = inputs(r);
  const DiagnoseOptions opt = options(r, t.model);
  const Diagnosis d = diagnose(in, opt);
  Outcome o;
  o.cpu_s = d.cpu_s;
  const std::string name = t.effect.empty() ? "" : effect_name(t.effect);
  const auto& ranked = d.ranking;  // after confirmation, as the JSON's candidates
  if (!ranked.empty() && ranked.front().testable) {
    o.first = ranked.front().name;
    o.ranked_first = o.first == name;
    for (const auto& g : ranked.front().group) o.in_first_group |= (g == name);
    o.in_first_group |= o.ranked_first;
  }
  o.verdict_any = d.changed();  // an effect or a noise: on a drive whose model is right, either is a false alarm
  for (const auto& a : d.add) o.verdict_has |= (a == name);
  for (const EffectEstimate& e : d.added_estimates)
    if (e.name == name) {
      const std::vector<double>& truth = r.injected_effects.at(name);
      o.estimate_error_sigmas = 0.0;
      for (int i = 0; i < e.value_si.size(); ++i)
        o.estimate_error_sigmas =
            std::max(o.estimate_error_sigmas, std::abs(e.value_si(i) - truth[static_cast<size_t>(i)]) / e.std_si(i));
    }
  o.err_base_m = d.truth_before.rms_pos_3d_m;
  o.err_after_m = d.truth_after.rms_pos_3d_m;
  if (with_reference && !name.empty()) {
    // The filter that knew the true model: the effect estimated, its prior centred on the true value.
    est::FilterOptions known = opt.model;
    known.add.push_back(name);
    const auto& truth = r.injected_effects.at(name);
    const Eigen::VectorXd value = Eigen::Map<const Eigen::VectorXd>(truth.data(), static_cast<long>(truth.size()));
    est::FilterOptions defaults;
    Eigen::VectorXd sd(value.size());
    if (name == "time_offset") sd(0) = defaults.time_offset_std_s;
    else sd = block_options(defaults, name)->init_std;
    set_prior(known, name, value, sd);
    const FilterRun ref = run_filter(in, known);
    o.err_ref_m = truth_error(ref, classify_epochs(ref.epochs), in.truth, opt.truth_skip_s).rms_pos_3d_m;
  }
  return o;
}

}  // namespace ldv::diag::testing
