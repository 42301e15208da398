#include "toolbox/allan/analysis.hpp"

#include "common/parallel/parallel_for.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "common/math/chi_square.hpp"
#include "toolbox/allan/edf.hpp"

namespace ldv::allan {

double close_bias_model_bic(long observations) {
  return std::max(6.0, std::log(static_cast<double>(std::max(2L, observations))));
}

std::vector<long> analysis_factors(const AnalysisOptions& opt, long n_phase, double tau0_s, Deviation dev) {
  const long dev_max = max_averaging_factor(dev, n_phase);
  if (!opt.taus_s.empty()) {
    std::vector<long> ms;
    for (double tau : opt.taus_s) {
      const long m = std::lround(tau / tau0_s);
      if (m < 1) throw std::invalid_argument("tau " + std::to_string(tau) + " s is shorter than the sample interval " + std::to_string(tau0_s) + " s");
      if (m > dev_max) {
        throw std::invalid_argument(std::string(deviation_name(dev)) + " at tau " + std::to_string(tau) +
                                    " s: the data is too short (" + std::to_string(n_phase - 1) + " samples allow tau <= " +
                                    std::to_string(dev_max * tau0_s) + " s)");
      }
      ms.push_back(m);
    }
    return ms;
  }
  long m_max = opt.max_factor > 0 ? std::min(opt.max_factor, dev_max) : std::min(default_max_factor(n_phase), dev_max);
  if (m_max < 1) m_max = std::min<long>(1, dev_max);
  return averaging_factors(opt.spacing, m_max, opt.per_decade);
}

namespace {

// The curve fit and, for inertial rates (not clock phase, whose noise types the model does not
// span), its refinement by the likelihood of the raw data, which keeps what the curve condenses away.
struct FitAttempt {
  std::optional<NoiseFit> curve, refined;
  std::optional<WhittleSummary> summary;
  std::string fit_error, likelihood_error;
};

FitAttempt fit_channel(const PhaseSeries& s, const std::vector<StabilityPoint>& weighted, const FitOptions& fo,
                       bool with_likelihood) {
  FitAttempt a;
  try {
    a.curve = fit_noise_model(weighted, fo);
  } catch (const std::invalid_argument& e) {
    a.fit_error = e.what();
    return a;
  }
  if (!with_likelihood) return a;
  try {
    WhittleSummary summary;
    a.refined = whittle_fit(s, *a.curve, fo, fo.likelihood_block_s, &summary);
    a.summary = summary;
  } catch (const std::invalid_argument& e) {
    a.likelihood_error = e.what();
  }
  return a;
}

// A Gauss-Markov the data hold apart from the other terms: its sigma's interval excludes 0, and its T's
// interval stays above the shortest T (a GM that may be that short is white where N shows, N's double).
bool gm_stands_out(const NoiseFit& fit, double gm_resolution_s) {
  const TermEstimate& gm = fit[ModelTerm::kGaussMarkov];
  return gm.in_model && gm.lo > 0.0 && !gm_time_constant_at_bound(gm.shape_lo, gm_resolution_s);
}

BiasModelCandidate candidate(const FitAttempt& a) {
  BiasModelCandidate c;
  c.fitted = a.refined.has_value();
  c.error = !a.fit_error.empty() ? a.fit_error : a.likelihood_error;
  if (!c.fitted) return c;
  const WhittleSummary& w = *a.summary;
  const double deviance = -2.0 * w.log_likelihood / w.taper_variance_factor;
  c.log_likelihood = w.log_likelihood;
  c.parameters = w.parameters;
  c.bic = deviance + w.parameters * std::log(static_cast<double>(std::max(2L, w.ordinates)));
  c.aic = deviance + 2.0 * w.parameters;
  return c;
}

ChannelResult analyze_channel(const PhaseSeries& s, const AnalysisOptions& opt) {
  ChannelResult r;
  r.name = s.name;
  r.unit = s.unit;
  r.tau0_s = s.tau0_s;
  r.samples = static_cast<long>(s.x.size()) - 1;
  r.mean_rate = s.mean_rate;
  const long n_phase = static_cast<long>(s.x.size());
  r.oadev = stability(s, Deviation::kOadev, analysis_factors(opt, n_phase, s.tau0_s, Deviation::kOadev), opt.confidence);
  if (opt.extra) {
    r.extra_kind = opt.extra;
    r.extra = stability(s, *opt.extra, analysis_factors(opt, n_phase, s.tau0_s, *opt.extra), opt.confidence);
  }
  if (opt.fit) {
    // Weights from the EDF: a noise type misidentified on a short averaged series (B1 ratio) can
    // claim white-PM-like degrees of freedom at long tau and pull the fit; never weight a point
    // above what white FM noise (angle/velocity random walk) would give it.
    std::vector<StabilityPoint> weighted = r.oadev;
    for (auto& p : weighted) p.edf = std::min(p.edf, greenhall_edf(Deviation::kOadev, 0, p.point.m, n_phase));
    const FitOptions& fo = opt.fit_options;
    const bool with_likelihood = fo.likelihood && s.source == DataKind::kFrequency && !fo.sinusoid;
    BiasModelChoice choice;
    choice.requested = fo.gauss_markov ? "gauss_markov" : fo.choose_bias_model ? "auto" : "flat";
    choice.criterion = "none";
    FitAttempt chosen = fit_channel(s, weighted, fo, with_likelihood);
    std::optional<NoiseFit> other_model;  // the likelihood fit of the bias model not chosen
    choice.chosen = fo.gauss_markov ? "gauss_markov" : "flat";
    if (choice.requested == "auto") {
      if (!fo.b) {
        choice.note = "no bias term in the model (--terms without B)";
      } else if (!with_likelihood) {
        choice.note = s.source != DataKind::kFrequency ? "phase input: no likelihood fit, flat B"
                      : fo.sinusoid                   ? "with a sinusoid: no likelihood fit, flat B"
                                                      : "curve fit only: flat B";
      } else if (!chosen.refined) {
        choice.note = "no likelihood fit of the flat B: " + (chosen.fit_error.empty() ? chosen.likelihood_error : chosen.fit_error);
        choice.flat = candidate(chosen);
      } else {
        // Both models on the same periodogram (same blocks, same ordinates): their Whittle
        // log-likelihoods compare directly. AIC (penalty 2 per parameter): what `ldv allan` writes is
        // a model that predicts the error growth (the filter's noise config), which is what AIC
        // chooses for (Kullback-Leibler). BIC's ln n (about 13 for hours of data) counts every
        // ordinate as evidence on the GM's T, which only the few around its corner carry: on the
        // paper's GM gyros it kept the flat B in 16-19 of 20 records at likelihood ratios mostly 4-12,
        // and the flat B took K 20-45 % high. AIC's risk, a GM that is not there when chance lifts
        // the likelihood by 1 (one record in six without a bias), is closed by asking the GM to
        // stand out (gm_stands_out).
        FitOptions g = fo;
        g.gauss_markov = true;
        FitAttempt gm = fit_channel(s, weighted, g, with_likelihood);
        choice.flat = candidate(chosen);
        choice.gauss_markov = candidate(gm);
        choice.observations = chosen.summary->ordinates;
        choice.taper_variance_factor = chosen.summary->taper_variance_factor;
        if (choice.gauss_markov.fitted) {
          choice.criterion = "AIC";
          choice.likelihood_ratio =
              2.0 * (choice.gauss_markov.log_likelihood - choice.flat.log_likelihood) / choice.taper_variance_factor;
          choice.gauss_markov_stands_out = gm_stands_out(*gm.refined, gm.summary->gm_resolution_s);
          if (choice.gauss_markov.aic < choice.flat.aic && !choice.gauss_markov_stands_out) {
            choice.note = "the Gauss-Markov's AIC is lower, but its sigma's interval reaches 0 or its T's the "
                          "white-noise bound: flat B";
          } else if (choice.gauss_markov.aic < choice.flat.aic) {
            std::swap(chosen, gm);  // gm now holds the flat B: the model not chosen
            choice.chosen = "gauss_markov";
          }
          if (std::abs(choice.flat.bic - choice.gauss_markov.bic) < close_bias_model_bic(choice.observations))
            other_model = std::move(gm.refined);
        } else {
          choice.note = "Gauss-Markov fit failed (" + choice.gauss_markov.error + "): flat B";
        }
      }
    }
    if (chosen.curve) {
      r.bias_model = choice;
      if (chosen.refined) {
        r.curve_fit = std::move(chosen.curve);
        r.fit = std::move(chosen.refined);
        r.likelihood = chosen.summary;
        // A close choice: N's and K's intervals span both models' (each term is in both).
        const auto span_both = [&](ModelTerm term) {
          TermEstimate& t = (*r.fit)[term];
          if (!other_model || !t.in_model || !(*other_model)[term].in_model) return false;
          t.lo = std::min(t.lo, (*other_model)[term].lo);
          t.hi = std::max(t.hi, (*other_model)[term].hi);
          return true;
        };
        r.n_interval_spans_both_bias_models = span_both(ModelTerm::kN);
        r.k_interval_spans_both_bias_models = span_both(ModelTerm::kK);
        try {
          r.information = record_information(*r.fit, s.tau0_s, r.samples, fo.likelihood_block_s, fo.target_precision);
        } catch (const std::invalid_argument& e) {
          r.likelihood_error = e.what();
        }
      } else {
        r.fit = std::move(chosen.curve);
        r.likelihood_error = chosen.likelihood_error;
      }
    } else {
      r.fit_error = chosen.fit_error;
    }
  }
  return r;
}

}  // namespace

std::vector<ChannelResult> analyze(const std::vector<PhaseSeries>& channels, const AnalysisOptions& opt,
                                   const Progress& progress) {
  std::vector<ChannelResult> results(channels.size());
  std::vector<std::exception_ptr> errors(channels.size());
  std::mutex progress_mutex;
  std::vector<size_t> order(channels.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  parallel_for(order, opt.threads, [&](size_t i) {
    try {
      results[i] = analyze_channel(channels[i], opt);
      if (progress) {
        std::lock_guard<std::mutex> lock(progress_mutex);
        progress("analysed " + channels[i].name);
      }
    } catch (...) {
      errors[i] = std::current_exception();
    }
  });
  for (auto& e : errors) if (e) std::rethrow_exception(e);
  return results;
}

}  // namespace ldv::allan
