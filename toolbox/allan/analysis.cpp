#include "toolbox/allan/analysis.hpp"

#include "common/parallel/parallel_for.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "toolbox/allan/edf.hpp"

namespace ldv::allan {

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
    try {
      // Weights from the EDF: a noise type misidentified on a short averaged series (B1 ratio) can
      // claim white-PM-like degrees of freedom at long tau and pull the fit; never weight a point
      // above what white FM noise (angle/velocity random walk) would give it.
      std::vector<StabilityPoint> weighted = r.oadev;
      for (auto& p : weighted) p.edf = std::min(p.edf, greenhall_edf(Deviation::kOadev, 0, p.point.m, n_phase));
      r.fit = fit_noise_model(weighted, opt.fit_options);
    } catch (const std::invalid_argument& e) {
      r.fit_error = e.what();
    }
    // Inertial rates (not clock phase, whose noise types the model does not span): refine by the
    // likelihood of the raw data, which keeps what the curve condenses away.
    const FitOptions& fo = opt.fit_options;
    if (r.fit && fo.likelihood && s.source == DataKind::kFrequency && !fo.sinusoid) {
      try {
        WhittleSummary summary;
        NoiseFit refined = whittle_fit(s, *r.fit, fo, fo.likelihood_block_s, &summary);
        r.curve_fit = std::move(r.fit);
        r.fit = std::move(refined);
        r.likelihood = summary;
        r.information = record_information(*r.fit, s.tau0_s, r.samples, fo.likelihood_block_s, fo.target_precision);
      } catch (const std::invalid_argument& e) {
        r.likelihood_error = e.what();
      }
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
