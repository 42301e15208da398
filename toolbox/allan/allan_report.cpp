#include "toolbox/allan/allan_report.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "common/formats/kfgins_config.hpp"
#include "common/io/output_file.hpp"
#include "toolbox/allan/sensor_units.hpp"

namespace ldv::allan {
namespace {

const ModelTerm kPaperTerms[5] = {ModelTerm::kQ, ModelTerm::kN, ModelTerm::kB, ModelTerm::kK, ModelTerm::kR};
const Term kUnitTerms[5] = {Term::kQ, Term::kN, Term::kB, Term::kK, Term::kR};

std::string num(double v) {
  if (!std::isfinite(v)) return "null";  // never NaN in JSON (and never expected)
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

std::string quoted(const std::string& s) {
  std::string o = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') o += '\\';
    o += c;
  }
  return o + "\"";
}

template <typename F>
std::string array_of(const std::vector<StabilityPoint>& pts, F get) {
  std::string o = "[";
  for (size_t i = 0; i < pts.size(); ++i) o += (i ? "," : "") + num(get(pts[i]));
  return o + "]";
}

// The estimate reported in the paper's row of term mt: B is the Gauss-Markov sigma when the
// bias is modelled as Gauss-Markov.
const TermEstimate& reported(const NoiseFit& f, ModelTerm mt) {
  return mt == ModelTerm::kB && f[ModelTerm::kGaussMarkov].in_model ? f[ModelTerm::kGaussMarkov] : f[mt];
}

std::string model_label(const std::string& m) { return m == "gauss_markov" ? "Gauss-Markov" : "flat B"; }

void print_bias_model(std::FILE* out, const BiasModelChoice& c) {
  if (c.criterion == "AIC") {
    // The criteria's differences, not their values: at millions of ordinates the values agree to 7 digits.
    std::fprintf(out,
                 "  bias model: %s, chosen by AIC: likelihood ratio %.3g for the Gauss-Markov (%d parameters, the flat B "
                 "%d); AIC flat - GM %.3g, BIC flat - GM %.3g (%ld ordinates); the Gauss-Markov %s\n",
                 model_label(c.chosen).c_str(), c.likelihood_ratio, c.gauss_markov.parameters, c.flat.parameters,
                 c.flat.aic - c.gauss_markov.aic, c.flat.bic - c.gauss_markov.bic, c.observations,
                 c.gauss_markov_stands_out ? "stands out"
                                           : "does not stand out (sigma's interval reaches 0 or T's the white bound)");
  } else if (c.requested == "auto") {
    std::fprintf(out, "  bias model: %s, not chosen by the data (%s)\n", model_label(c.chosen).c_str(), c.note.c_str());
  } else {
    std::fprintf(out, "  bias model: %s, as asked (--bias-model %s)\n", model_label(c.chosen).c_str(),
                 c.requested == "gauss_markov" ? "gm" : "flat");
  }
}

std::string candidate_json(const BiasModelCandidate& c) {
  std::string o = std::string("{\"fitted\": ") + (c.fitted ? "true" : "false");
  if (c.fitted) {
    o += ", \"log_likelihood\": " + num(c.log_likelihood) + ", \"parameters\": " + std::to_string(c.parameters) +
         ", \"bic\": " + num(c.bic) + ", \"aic\": " + num(c.aic);
  } else {
    o += ", \"error\": " + quoted(c.error);
  }
  return o + "}";
}

}  // namespace

BiasProcess bias_process(const NoiseFit& fit) {
  const TermEstimate& gm = fit[ModelTerm::kGaussMarkov];
  if (gm.in_model) return {gm.value, gm.shape};
  const double floor_adev = std::sqrt(2.0 * std::log(2.0) / M_PI) * fit[ModelTerm::kB].value;
  return {floor_adev / 0.6174, fit.b_tau_s / 1.893};
}

void print_tables(std::FILE* out, const std::vector<ChannelResult>& results) {
  for (const ChannelResult& r : results) {
    const Quantity q = quantity_of_si_unit(r.unit);
    std::fprintf(out, "\n%s [%s]: %ld samples at %.6g s (%.2f h), mean %.6g %s removed\n", r.name.c_str(), r.unit.c_str(),
                 r.samples, r.tau0_s, r.samples * r.tau0_s / 3600.0, r.mean_rate, r.unit.c_str());
    if (!r.fit) {
      std::fprintf(out, "  no noise fit: %s\n", r.fit_error.c_str());
      continue;
    }
    const NoiseFit& f = *r.fit;
    if (r.likelihood) {
      std::fprintf(out, "  N, B, K, R: likelihood of the raw data (Whittle; blocks of %.4g s, %ld ordinates); Q: Allan-curve fit\n",
                   r.likelihood->block_s, r.likelihood->ordinates);
    } else {
      std::fprintf(out, "  fit to the Allan variance curve (%s)%s%s\n", f.gls ? "generalized LS" : "weighted LS",
                   r.likelihood_error.empty() ? "" : "; no likelihood fit: ", r.likelihood_error.c_str());
    }
    if (r.bias_model) print_bias_model(out, *r.bias_model);
    std::fprintf(out, "  %-4s %-15s %12s %12s %25s  %-9s %12s %12s\n", "term", "unit", "value", "sigma", "95% interval",
                 "resolved", "slope line", r.curve_fit ? "curve fit" : "");
    for (int i = 0; i < 5; ++i) {
      const ModelTerm mt = kPaperTerms[i];
      const EngineeringUnit u = paper_unit(q, kUnitTerms[i]);
      const TermEstimate* t = &reported(f, mt);
      const TermEstimate* curve = r.curve_fit ? &reported(*r.curve_fit, mt) : nullptr;
      std::string extra;
      if (mt == ModelTerm::kB && f[ModelTerm::kGaussMarkov].in_model) {
        char buf[96];
        if (t->shape_hi > 0.0)
          std::snprintf(buf, sizeof buf, "  (Gauss-Markov, T = %.4g s, 95%% [%.4g, %.4g])", t->shape, t->shape_lo,
                        t->shape_hi);
        else
          std::snprintf(buf, sizeof buf, "  (Gauss-Markov, T = %.4g s)", t->shape);
        extra = buf;
      } else if (mt == ModelTerm::kB) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "  (flat at tau = %.4g s)", f.b_tau_s);
        extra = buf;
      }
      if (!t->in_model) {
        std::fprintf(out, "  %-4s %-15s %12s\n", term_name(kUnitTerms[i]), u.name, "not modelled");
        continue;
      }
      char interval[64];
      std::snprintf(interval, sizeof interval, "[%.4g, %.4g]", t->lo * u.from_si, t->hi * u.from_si);
      char curve_value[32] = "";
      if (curve) std::snprintf(curve_value, sizeof curve_value, "%.5g", curve->value * u.from_si);
      std::fprintf(out, "  %-4s %-15s %12.5g %12.3g %25s  %-9s %12.5g %12s%s\n", term_name(kUnitTerms[i]), u.name,
                   t->value * u.from_si, t->sigma * u.from_si, interval, t->resolved ? "yes" : "no",
                   f.slope_lines[i].value * u.from_si, curve_value, extra.c_str());
    }
    const TermEstimate& sine = f[ModelTerm::kSinusoid];
    if (sine.in_model) {
      std::fprintf(out, "  sine amplitude %.5g %s at %.5g Hz (%s)\n", sine.value, r.unit.c_str(), sine.shape,
                   sine.resolved ? "resolved" : "not resolved");
    }
    // What the intervals carry beyond the fit's own information.
    const bool n_both = r.n_interval_spans_both_bias_models, k_both = r.k_interval_spans_both_bias_models;
    if (n_both || k_both)
      std::fprintf(out, "  intervals: %s both bias models' (the models are close: |BIC flat - GM| < ln n)\n",
                   n_both && k_both ? "N's and K's span"
                   : n_both         ? "N's spans"
                                    : "K's spans");
    if (r.information) {
      const RecordInformation& info = *r.information;
      const bool gm = f[ModelTerm::kGaussMarkov].in_model;
      const double b_now = gm ? info.now.gm_sigma : info.now.b;
      auto hours = [](double h) {
        char buf[32];
        if (h == 0.0) return std::string("-");
        if (!std::isfinite(h)) return std::string("> 1000 h");
        if (h < 1.0 / 60.0) std::snprintf(buf, sizeof buf, "%.2g s", h * 3600.0);
        else if (h < 1.0) std::snprintf(buf, sizeof buf, "%.2g min", h * 60.0);
        else std::snprintf(buf, sizeof buf, "%.3g h", h);
        return std::string(buf);
      };
      std::fprintf(out, "  information in this record (%.3g h; Cramer-Rao, fit taken as truth): sd N %.2g %%, B %.2g %%, K %.2g %%\n",
                   r.samples * r.tau0_s / 3600.0, 100 * info.now.n, 100 * b_now, 100 * info.now.k);
      std::fprintf(out, "  record needed for %.3g %% (1 sigma) on each resolved term (- not resolved): N %s, B %s, K %s\n", 100 * info.target,
                   hours(info.hours_n).c_str(), hours(info.hours_b).c_str(), hours(info.hours_k).c_str());
    }
    std::fprintf(out, "  misfit per decade (chi2/point ~ 1 when the model fits):\n");
    for (const DecadeMisfit& m : f.misfit) {
      std::fprintf(out, "    tau %8.3g..%-8.3g s: %3d points, chi2/point %8.3g, data/model %6.3f", m.tau_lo_s, m.tau_hi_s,
                   m.points, m.chi2_per_point, std::exp(m.log_ratio));
      if (!m.closing_term.empty()) {
        std::fprintf(out, "  -> add %s: chi2/point %.3g", m.closing_term.c_str(), m.chi2_per_point_with_term);
      }
      std::fprintf(out, "\n");
    }
  }
}

void write_json(const std::string& path, const std::string& input, const std::vector<ChannelResult>& results,
                const AnalysisOptions& opt) {
  std::ostringstream o;
  o << "{\n  \"tool\": \"ldv allan\",\n  \"schema_version\": 1,\n  \"input\": " << quoted(input)
    << ",\n  \"confidence\": " << num(opt.confidence) << ",\n  \"interval_confidence\": "
    << num(opt.fit_options.interval_confidence) << ",\n  \"channels\": [";
  for (size_t c = 0; c < results.size(); ++c) {
    const ChannelResult& r = results[c];
    o << (c ? "," : "") << "\n    {\n      \"name\": " << quoted(r.name) << ",\n      \"unit\": " << quoted(r.unit)
      << ",\n      \"tau0_s\": " << num(r.tau0_s) << ",\n      \"samples\": " << r.samples
      << ",\n      \"mean\": " << num(r.mean_rate);
    o << ",\n      \"taus_s\": " << array_of(r.oadev, [](const StabilityPoint& p) { return p.point.tau_s; });
    o << ",\n      \"oadev\": " << array_of(r.oadev, [](const StabilityPoint& p) { return p.point.dev; });
    o << ",\n      \"oadev_lo\": " << array_of(r.oadev, [](const StabilityPoint& p) { return p.interval.lo; });
    o << ",\n      \"oadev_hi\": " << array_of(r.oadev, [](const StabilityPoint& p) { return p.interval.hi; });
    o << ",\n      \"oadev_n\": " << array_of(r.oadev, [](const StabilityPoint& p) { return double(p.point.n_terms); });
    o << ",\n      \"edf\": " << array_of(r.oadev, [](const StabilityPoint& p) { return p.edf; });
    o << ",\n      \"alpha\": " << array_of(r.oadev, [](const StabilityPoint& p) { return double(p.alpha); });
    if (r.fit) {
      const NoiseFit& f = *r.fit;
      const Quantity q = quantity_of_si_unit(r.unit);
      const bool gm = f[ModelTerm::kGaussMarkov].in_model;
      for (int i = 0; i < 5; ++i) {
        const ModelTerm mt = kPaperTerms[i];
        const TermEstimate& t = reported(f, mt);
        const std::string n = term_name(kUnitTerms[i]);
        o << ",\n      \"" << n << "\": " << num(t.value) << ", \"" << n << "_sigma\": " << num(t.sigma) << ", \"" << n
          << "_lo\": " << num(t.lo) << ", \"" << n << "_hi\": " << num(t.hi) << ", \"" << n
          << "_resolved\": " << (t.resolved ? "true" : "false") << ", \"" << n
          << "_modelled\": " << (t.in_model ? "true" : "false");
      }
      o << ",\n      \"N_interval_spans_both_bias_models\": "
        << (r.n_interval_spans_both_bias_models ? "true" : "false")
        << ", \"K_interval_spans_both_bias_models\": " << (r.k_interval_spans_both_bias_models ? "true" : "false");
      o << ",\n      \"B_tau_s\": " << num(f.b_tau_s) << ", \"B_model\": " << quoted(gm ? "gauss_markov" : "flat")
        << ", \"B_T_s\": " << num(gm ? f[ModelTerm::kGaussMarkov].shape : 0.0)
        << ", \"B_T_s_sigma\": " << num(gm ? f[ModelTerm::kGaussMarkov].shape_sigma : 0.0)
        << ", \"B_T_s_lo\": " << num(gm ? f[ModelTerm::kGaussMarkov].shape_lo : 0.0)
        << ", \"B_T_s_hi\": " << num(gm ? f[ModelTerm::kGaussMarkov].shape_hi : 0.0);
      if (r.bias_model) {  // how B_model was chosen (README.md, "Bias model")
        const BiasModelChoice& bm = *r.bias_model;
        o << ",\n      \"bias_model_selection\": {\"requested\": " << quoted(bm.requested)
          << ", \"criterion\": " << quoted(bm.criterion) << ", \"chosen\": " << quoted(bm.chosen)
          << ", \"note\": " << quoted(bm.note);
        if (bm.flat.fitted || !bm.flat.error.empty() || bm.gauss_markov.fitted || !bm.gauss_markov.error.empty()) {
          o << ", \"observations\": " << bm.observations << ", \"taper_variance_factor\": " << num(bm.taper_variance_factor);
          if (bm.criterion == "AIC") {
            o << ", \"likelihood_ratio\": " << num(bm.likelihood_ratio)
              << ", \"delta_aic\": " << num(bm.flat.aic - bm.gauss_markov.aic)
              << ", \"delta_bic\": " << num(bm.flat.bic - bm.gauss_markov.bic)
              << ", \"gauss_markov_stands_out\": " << (bm.gauss_markov_stands_out ? "true" : "false");
          }
          o << ", \"flat\": " << candidate_json(bm.flat) << ", \"gauss_markov\": " << candidate_json(bm.gauss_markov);
        }
        o << "}";
      }
      const TermEstimate& sine = f[ModelTerm::kSinusoid];
      if (sine.in_model) {
        o << ",\n      \"sine_amplitude\": " << num(sine.value) << ", \"sine_amplitude_sigma\": " << num(sine.sigma)
          << ", \"sine_hz\": " << num(sine.shape) << ", \"sine_resolved\": " << (sine.resolved ? "true" : "false");
      }
      o << ",\n      \"units\": {";
      for (int i = 0; i < 5; ++i) o << (i ? ", " : "") << "\"" << term_name(kUnitTerms[i]) << "\": " << quoted(si_term_unit(r.unit, kUnitTerms[i]));
      o << "}";
      o << ",\n      \"paper_units\": {";
      for (int i = 0; i < 5; ++i) {
        const EngineeringUnit u = paper_unit(q, kUnitTerms[i]);
        const ModelTerm mt = kPaperTerms[i];
        const TermEstimate& t = reported(f, mt);
        o << (i ? ", " : "") << "\"" << term_name(kUnitTerms[i]) << "\": {\"value\": " << num(t.value * u.from_si)
          << ", \"sigma\": " << num(t.sigma * u.from_si) << ", \"unit\": " << quoted(u.name) << "}";
      }
      o << "}";
      o << ",\n      \"slope_lines\": {";
      for (int i = 0; i < 5; ++i) {
        o << (i ? ", " : "") << "\"" << term_name(kUnitTerms[i]) << "\": {\"value\": " << num(f.slope_lines[i].value)
          << ", \"tau_s\": " << num(f.slope_lines[i].tau_s) << "}";
      }
      o << "}";
      o << ",\n      \"fit\": {\"method\": " << quoted(f.method) << ", \"chi2\": " << num(f.chi2) << ", \"points\": " << f.points
        << ", \"covariance_inflation\": " << num(f.covariance_inflation)
        << ", \"gls\": " << (f.gls ? "true" : "false");
      if (r.likelihood) {
        o << ", \"likelihood_block_s\": " << num(r.likelihood->block_s)
          << ", \"gm_resolution_s\": " << num(r.likelihood->gm_resolution_s) << ", \"likelihood_ordinates\": "
          << r.likelihood->ordinates << ", \"log_likelihood\": " << num(r.likelihood->log_likelihood);
      }
      o << "}";
      if (r.information) {
        const RecordInformation& info = *r.information;
        const double b_now = gm ? info.now.gm_sigma : info.now.b;
        o << ",\n      \"record_information\": {\"target_relative_sd\": " << num(info.target)
          << ", \"relative_sd\": {\"N\": " << num(info.now.n) << ", \"B\": " << num(b_now) << ", \"K\": " << num(info.now.k)
          << "}, \"hours_for_target\": {\"N\": " << num(info.hours_n) << ", \"B\": " << num(info.hours_b)
          << ", \"K\": " << num(info.hours_k) << "}}";
      }
      if (r.curve_fit) {  // the Allan-curve fit the likelihood started from: the second opinion
        const NoiseFit& cf = *r.curve_fit;
        o << ",\n      \"allan_curve_fit\": {\"method\": " << quoted(cf.method);
        for (int i = 0; i < 5; ++i) {
          const ModelTerm mt = kPaperTerms[i];
          const TermEstimate& t = reported(cf, mt);
          o << ", \"" << term_name(kUnitTerms[i]) << "\": {\"value\": " << num(t.value) << ", \"sigma\": " << num(t.sigma)
            << ", \"lo\": " << num(t.lo) << ", \"hi\": " << num(t.hi) << ", \"resolved\": " << (t.resolved ? "true" : "false") << "}";
        }
        o << "}";
      }
      o << ",\n      \"misfit\": [";
      for (size_t i = 0; i < f.misfit.size(); ++i) {
        const DecadeMisfit& m = f.misfit[i];
        o << (i ? "," : "") << "\n        {\"tau_lo_s\": " << num(m.tau_lo_s) << ", \"tau_hi_s\": " << num(m.tau_hi_s)
          << ", \"points\": " << m.points << ", \"chi2_per_point\": " << num(m.chi2_per_point)
          << ", \"data_over_model\": " << num(std::exp(m.log_ratio)) << ", \"closing_term\": " << quoted(m.closing_term)
          << ", \"chi2_per_point_with_term\": " << num(m.chi2_per_point_with_term) << "}";
      }
      o << "]";
    } else {
      o << ",\n      \"fit_error\": " << quoted(r.fit_error);
    }
    if (r.extra_kind) {
      const char* k = deviation_name(*r.extra_kind);
      o << ",\n      \"deviation\": {\"kind\": " << quoted(k)
        << ", \"taus_s\": " << array_of(r.extra, [](const StabilityPoint& p) { return p.point.tau_s; })
        << ", \"dev\": " << array_of(r.extra, [](const StabilityPoint& p) { return p.point.dev; })
        << ", \"lo\": " << array_of(r.extra, [](const StabilityPoint& p) { return p.interval.lo; })
        << ", \"hi\": " << array_of(r.extra, [](const StabilityPoint& p) { return p.interval.hi; })
        << ", \"n\": " << array_of(r.extra, [](const StabilityPoint& p) { return double(p.point.n_terms); }) << "}";
    }
    o << "\n    }";
  }
  o << "\n  ]\n}\n";
  std::ofstream f(path);
  if (!f) throw std::runtime_error("cannot write " + path);
  f << o.str();
  close_checked(f, path);  // a full disk shows at the flush
}

std::string kfgins_noise_yaml(const std::vector<ChannelResult>& results) {
  std::vector<const ChannelResult*> gyro, accel;
  for (const auto& r : results) {
    if (!r.fit) continue;
    if (r.unit == "rad/s") gyro.push_back(&r);
    if (r.unit == "m/s^2") accel.push_back(&r);
  }
  if (gyro.empty() && accel.empty()) return "";
  const double deg = M_PI / 180.0;
  auto term = [](const NoiseFit& f, ModelTerm t) { return f[t].in_model ? f[t].value : 0.0; };
  // KF-GINS has one correlation time: the median over the channels; its gbstd/abstd carry K as well
  // (kfgins_single_bias_std), as `ldv sim` writes them.
  std::vector<double> taus;
  for (const auto* ch : {&gyro, &accel})
    for (const ChannelResult* r : *ch) taus.push_back(bias_process(*r->fit).time_constant_s);
  std::nth_element(taus.begin(), taus.begin() + taus.size() / 2, taus.end());
  const double corr_time_s = taus[taus.size() / 2];
  std::ostringstream o;
  auto list = [&](const std::vector<const ChannelResult*>& ch, auto value) {
    o << "[";
    for (size_t i = 0; i < 3; ++i) {
      // KF-GINS wants three axes: repeat the last channel when fewer were analysed.
      const ChannelResult* r = ch[std::min(i, ch.size() - 1)];
      char buf[32];
      std::snprintf(buf, sizeof buf, "%.6g", value(*r->fit));
      o << (i ? ", " : "") << buf;
    }
    o << "]";
  };
  auto single_bias = [&](const NoiseFit& f) {
    return kfgins_single_bias_std(bias_process(f).sigma, term(f, ModelTerm::kK), corr_time_s);
  };
  o << "# ldv allan: noise for ldv nav (KF-GINS imunoise keys, engineering units)\nimunoise:\n";
  if (!gyro.empty()) {
    o << "  arw: ";
    list(gyro, [&](const NoiseFit& f) { return f[ModelTerm::kN].value * 60.0 / deg; });
    o << "    # [deg/sqrt(h)]\n  gbstd: ";
    list(gyro, [&](const NoiseFit& f) { return single_bias(f) * 3600.0 / deg; });
    o << "    # [deg/h] Gauss-Markov sigma and K over corrtime\n";
  }
  if (!accel.empty()) {
    o << "  vrw: ";
    list(accel, [&](const NoiseFit& f) { return f[ModelTerm::kN].value * 60.0; });
    o << "    # [m/s/sqrt(h)]\n  abstd: ";
    list(accel, [&](const NoiseFit& f) { return single_bias(f) * 1e5; });
    o << "    # [mGal] Gauss-Markov sigma and K over corrtime\n";
  }
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", corr_time_s / 3600.0);
  o << "  corrtime: " << buf << "    # [h] median over the channels (KF-GINS has one)\n";
  // geoldv51's moving bias per term (SI; estimator/run/run_navigation.cpp reads them): the Gauss-Markov
  // sigma with the triad's mean time constant, the rate random walk K and the ramp R.
  o << "ldv:  # geoldv51's moving bias per term, SI (ldv nav --model geoldv51)\n";
  for (const auto& [ch, prefix, gm, rw, ramp] :
       {std::tuple{&gyro, "moving_bias_gyro_", "gm_rad_s", "rw_rad_s_sqrt_s", "ramp_rad_s2"},
        std::tuple{&accel, "moving_bias_accel_", "gm_mps2", "rw_mps2_sqrt_s", "ramp_mps3"}}) {
    if (ch->empty()) continue;
    double sum_t = 0.0;
    for (const ChannelResult* r : *ch) sum_t += bias_process(*r->fit).time_constant_s;
    o << "  " << prefix << gm << ": ";
    list(*ch, [&](const NoiseFit& f) { return bias_process(f).sigma; });
    std::snprintf(buf, sizeof buf, "%.6g", sum_t / static_cast<double>(ch->size()));
    o << "\n  " << prefix << "gm_time_s: " << buf << "\n  " << prefix << rw << ": ";
    list(*ch, [&](const NoiseFit& f) { return term(f, ModelTerm::kK); });
    o << "\n  " << prefix << ramp << ": ";
    list(*ch, [&](const NoiseFit& f) { return term(f, ModelTerm::kR); });
    o << "\n";
  }
  // The gyros' Q [rad/s * s = rad]: a white error of the integrated angle, whose tilt of the specific force ldv nav
  // adds to the velocity noise.
  if (!gyro.empty()) {
    o << "  gyro_quantization_rad: ";
    list(gyro, [&](const NoiseFit& f) { return term(f, ModelTerm::kQ); });
    o << "\n";
  }
  return o.str();
}

}  // namespace ldv::allan
