#pragma once
// Confirmation: rerun the filter with a candidate added (its prior centred on the screening estimate)
// and compare the innovation log-likelihood with the model without it, penalised BIC-style on the
// effective sample size. The gain is divided by the long-run factor of the innovations (correlated
// innovations inflate likelihood differences by about that factor).
#include <string>

#include "toolbox/diagnose/filter_run.hpp"
#include "toolbox/diagnose/score_test.hpp"

namespace ldv::diag {

struct Confirmation {
  std::string effect;
  double loglik_gain = 0.0;      // log L(with) - log L(without)
  double adjusted_gain = 0.0;    // gain / long-run factor
  double penalty = 0.0;          // 0.5 dim log(N_eff)
  bool accepted = false;         // adjusted gain > penalty
  est::FilterOptions options;    // the model with the effect added
  FilterRun run;
  EffectEstimate estimate;       // the rerun's final estimate of the added effect
};

// Adds `score.name` to `model` with its prior centred on the screening estimate.
est::FilterOptions with_candidate(const est::FilterOptions& model, const CandidateScore& score);

Confirmation confirm(const DiagnoseInputs& in, const est::FilterOptions& model, double base_loglik,
                     const CandidateScore& score, double long_run_factor, double effective_n);

}  // namespace ldv::diag
