#pragma once
// Confirmation: rerun the filter with a candidate added (its prior centred on the screening estimate)
// and compare the innovation log-likelihood with the model without it, penalised BIC-style on the
// effective sample size. The gain is divided by the long-run factor of the innovations (correlated
// innovations inflate likelihood differences by about that factor).
#include <string>
#include <utility>
#include <vector>

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
  int filter_runs = 1;           // the reruns it took (a noise factor's likelihood search takes several)
};

// The rerun `c.run` of `c.options` judged against `base`: the gain over the measurements both used, deflated by the
// long-run factor, against the BIC penalty of `dim` parameters. Effects and noise factors are judged alike.
void judge_rerun(Confirmation& c, const FilterRun& base, int dim, double long_run_factor, double effective_n);

// Adds `score.name` to `model` with its prior centred on the screening estimate.
est::FilterOptions with_candidate(const est::FilterOptions& model, const CandidateScore& score);

// The rerun's log-likelihood gain is over the measurements both runs used: an added time offset can move the first fix
// before the IMU's start, and that fix's term (its ln det S at the initial covariance) alone gained 286 for a 1 ms
// offset on a drive whose only effect was a 3 cm lever arm.
Confirmation confirm(const DiagnoseInputs& in, const est::FilterOptions& model, const FilterRun& base,
                     const CandidateScore& score, double long_run_factor, double effective_n);

// log L of `a` and of `b` over the measurements both hold (per sensor, paired within half its median interval), each
// capped as log_likelihood caps it at the gate of gate_probability.
std::pair<double, double> log_likelihoods_over_common(const std::vector<SensitivityRecord>& a,
                                                      const std::vector<SensitivityRecord>& b, double gate_probability);

}  // namespace ldv::diag
