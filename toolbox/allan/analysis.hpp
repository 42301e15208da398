#pragma once
// One call from phase series to results: the overlapping Allan deviation with confidence intervals
// on the chosen tau list, the noise fit, and optionally a raw table of another deviation.
// Channels run in parallel (one thread per core).
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "toolbox/allan/confidence.hpp"
#include "toolbox/allan/noise_fit.hpp"
#include "toolbox/allan/phase_series.hpp"
#include "toolbox/allan/tau_list.hpp"
#include "toolbox/allan/whittle_fit.hpp"

namespace ldv::allan {

struct AnalysisOptions {
  TauSpacing spacing = TauSpacing::kLog;
  int per_decade = 10;
  long max_factor = 0;                   // 0: N/4
  std::vector<double> taus_s;            // explicit taus (override spacing); each must fit the data
  std::optional<Deviation> extra;        // a raw table of this deviation too
  double confidence = kOneSigmaConfidence;
  bool fit = true;
  FitOptions fit_options;
  int threads = 0;                       // 0: hardware concurrency
};

// One bias model's likelihood fit, as the choice between them saw it.
struct BiasModelCandidate {
  bool fitted = false;        // false: its fit failed (`error`)
  std::string error;
  double log_likelihood = 0.0;  // Whittle log-likelihood of the tapered data (WhittleSummary)
  int parameters = 0;           // free parameters (WhittleSummary::parameters)
  double bic = 0.0, aic = 0.0;  // -2 lnL / taper factor + k ln(ordinates), resp. + 2k
};

// How the bias model (flat B or Gauss-Markov) was chosen. With FitOptions::choose_bias_model (the
// default) and rate input with the likelihood fit, both models are fitted to the same periodogram
// and the lower AIC wins when the GM stands out (its sigma's interval excludes 0, its T's stays off the
// white-noise bound); ties and a GM that does not stand out: the flat B, one parameter fewer. Otherwise
// the model asked for (or the flat B when the likelihood fit does not run) and `note` says why.
struct BiasModelChoice {
  std::string requested;  // "auto" | "flat" | "gauss_markov"
  std::string criterion;  // "AIC" when chosen by the data, else "none"
  std::string chosen;     // "flat" | "gauss_markov"
  std::string note;       // why not chosen by the data ("" when it was)
  long observations = 0;  // periodogram ordinates: the n of the BIC
  double taper_variance_factor = 1.0;
  // 2 (lnL_gm - lnL_flat) / taper factor: the likelihood-ratio statistic (> 0 favours the GM)
  double likelihood_ratio = 0.0;
  // (criterion "AIC") the GM fit's sigma interval excludes 0 and its T's stays off the white-noise bound
  bool gauss_markov_stands_out = false;
  BiasModelCandidate flat, gauss_markov;
};

struct ChannelResult {
  std::string name, unit;
  double tau0_s = 0.0;
  long samples = 0;                      // phase points - 1
  double mean_rate = 0.0;                // removed mean (bias), unit
  std::vector<StabilityPoint> oadev;
  std::vector<StabilityPoint> extra;     // empty unless AnalysisOptions::extra
  std::optional<Deviation> extra_kind;
  std::optional<NoiseFit> fit;           // empty when fewer than 3 points or fit disabled
  std::string fit_error;                 // why there is no fit
  // With the likelihood refinement: `fit` is it, `curve_fit` the Allan-curve fit it started from
  // (a second opinion), `likelihood` its summary. `likelihood_error`: why it was not applied.
  std::optional<NoiseFit> curve_fit;
  std::optional<WhittleSummary> likelihood;
  std::optional<RecordInformation> information;  // with the likelihood fit: bounds, record needed
  std::string likelihood_error;
  std::optional<BiasModelChoice> bias_model;  // with a fit: how its bias model was chosen
  // What the likelihood fit's intervals carry beyond its own Fisher information (README.md, "Intervals"): when
  // the bias models are close in BIC (close_bias_model_bic; whichever AIC took), N's and K's intervals
  // span both models' (each is in both; the flat B and the GM sigma are different quantities and keep their own).
  bool n_interval_spans_both_bias_models = false;
  bool k_interval_spans_both_bias_models = false;
};

// BIC's margin below which the choice of the bias model is close: one parameter's penalty, ln(ordinates) (BIC
// then took the flat B although the GM fits as well or better: on the paper's HG1900 the GM's K is right and the
// flat B's 7-9 % high, outside its own interval), and at least 6 (Kass & Raftery 1995: below 6, "positive" at
// most). AIC chooses the model since; this margin still says when both models' N and K intervals are plausible.
double close_bias_model_bic(long observations);

// Averaging factors for a channel: explicit taus rounded to whole samples (std::invalid_argument
// when one is below tau0 or beyond the data), or the spacing up to the maximum factor.
std::vector<long> analysis_factors(const AnalysisOptions& opt, long n_phase, double tau0_s, Deviation dev);

using Progress = std::function<void(const std::string&)>;

std::vector<ChannelResult> analyze(const std::vector<PhaseSeries>& channels, const AnalysisOptions& opt,
                                   const Progress& progress = nullptr);

}  // namespace ldv::allan
