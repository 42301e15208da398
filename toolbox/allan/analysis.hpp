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
};

// Averaging factors for a channel: explicit taus rounded to whole samples (std::invalid_argument
// when one is below tau0 or beyond the data), or the spacing up to the maximum factor.
std::vector<long> analysis_factors(const AnalysisOptions& opt, long n_phase, double tau0_s, Deviation dev);

using Progress = std::function<void(const std::string&)>;

std::vector<ChannelResult> analyze(const std::vector<PhaseSeries>& channels, const AnalysisOptions& opt,
                                   const Progress& progress = nullptr);

}  // namespace ldv::allan
