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

Confirmation confirm(const DiagnoseInputs& in, const est::FilterOptions& model, double base_loglik,
                     const CandidateScore& score, double long_run_factor, double effective_n) {
  Confirmation c;
  c.effect = score.name;
  c.options = with_candidate(model, score);
  c.run = run_filter(in, c.options);
  c.loglik_gain = log_likelihood(c.run.records, c.run.gate_probability) - base_loglik;
  c.adjusted_gain = c.loglik_gain / std::max(1.0, long_run_factor);
  c.penalty = 0.5 * score.dim * std::log(std::max(2.0, effective_n));
  c.accepted = c.adjusted_gain > c.penalty;
  for (const EffectEstimate& e : c.run.estimates)
    if (e.name == score.name) c.estimate = e;
  return c;
}

}  // namespace ldv::diag
