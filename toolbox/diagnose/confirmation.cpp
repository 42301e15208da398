#include "toolbox/diagnose/confirmation.hpp"

#include <algorithm>
#include <cmath>

#include "estimator/effects/registry.hpp"
#include "toolbox/diagnose/model_check.hpp"

namespace ldv::diag {

est::FilterOptions with_candidate(const est::FilterOptions& model, const CandidateScore& score) {
  est::FilterOptions o = model;
  o.add.push_back(score.name);
  std::erase(o.drop, score.name);
  // Prior: the configured prior of the block, centred on the screening estimate and wide enough to hold
  // it (a hidden lever arm of 1 m must not be fought by a 5 cm prior).
  const auto effect = est::effect_registry().make(score.name, o);
  Eigen::VectorXd mean(effect->dim()), sd(effect->dim());
  effect->prior(mean, sd);
  for (int i = 0; i < effect->dim(); ++i) {
    if (!std::isfinite(score.estimate_si(i))) continue;
    mean(i) = score.estimate_si(i);
    sd(i) = std::max({sd(i), 3.0 * score.sigma_si(i), 0.3 * std::abs(score.estimate_si(i))});
  }
  set_prior(o, score.name, mean, sd);
  return o;
}

std::pair<double, double> log_likelihoods_over_common(const std::vector<SensitivityRecord>& a,
                                                      const std::vector<SensitivityRecord>& b,
                                                      double gate_probability) {
  // Per sensor, each record of `a` with the first unmatched one of `b` within half the sensor's median interval: a
  // time offset state applies every fix at a shifted IMU epoch (the records' t_s), so times match only to it.
  double ll_a = 0.0, ll_b = 0.0;
  std::vector<est::SensorName> sensors;
  for (const SensitivityRecord& r : a)
    if (std::find(sensors.begin(), sensors.end(), r.sensor) == sensors.end()) sensors.push_back(r.sensor);
  for (const est::SensorName sensor : sensors) {
    std::vector<const SensitivityRecord*> ra, rb;
    for (const SensitivityRecord& r : a)
      if (r.sensor == sensor) ra.push_back(&r);
    for (const SensitivityRecord& r : b)
      if (r.sensor == sensor) rb.push_back(&r);
    std::vector<double> intervals;
    for (size_t k = 1; k < ra.size(); ++k) intervals.push_back(ra[k]->t_s - ra[k - 1]->t_s);
    double half_s = 1e-4;
    if (!intervals.empty()) {
      std::nth_element(intervals.begin(), intervals.begin() + static_cast<long>(intervals.size() / 2), intervals.end());
      half_s = std::max(half_s, 0.5 * intervals[intervals.size() / 2]);
    }
    size_t j = 0;
    for (const SensitivityRecord* r : ra) {
      while (j < rb.size() && rb[j]->t_s < r->t_s - half_s) ++j;
      if (j < rb.size() && rb[j]->t_s <= r->t_s + half_s && rb[j]->innovation.size() == r->innovation.size()) {
        ll_a += log_likelihood_term(*r, gate_probability);
        ll_b += log_likelihood_term(*rb[j], gate_probability);
        ++j;
      }
    }
  }
  return {ll_a, ll_b};
}

void judge_rerun(Confirmation& c, const FilterRun& base, int dim, double long_run_factor, double effective_n) {
  const auto [base_ll, with_ll] = log_likelihoods_over_common(base.records, c.run.records, c.run.gate_probability);
  c.loglik_gain = with_ll - base_ll;
  c.adjusted_gain = c.loglik_gain / std::max(1.0, long_run_factor);
  c.penalty = 0.5 * dim * std::log(std::max(2.0, effective_n));
  c.accepted = c.adjusted_gain > c.penalty;
}

Confirmation confirm(const DiagnoseInputs& in, const est::FilterOptions& model, const FilterRun& base,
                     const CandidateScore& score, double long_run_factor, double effective_n) {
  Confirmation c;
  c.effect = score.name;
  c.options = with_candidate(model, score);
  c.run = run_filter(in, c.options);
  judge_rerun(c, base, score.dim, long_run_factor, effective_n);
  for (const EffectEstimate& e : c.run.estimates)
    if (e.name == score.name) c.estimate = e;
  return c;
}

}  // namespace ldv::diag
