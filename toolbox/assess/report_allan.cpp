// Report section: Allan deviation of each channel of an `ldv allan --json` file with the fitted noise
// terms (quantisation Q, white N, bias instability B or a Gauss-Markov bias, random walk K, ramp R).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "common/plot/gnuplot.hpp"
#include "toolbox/assess/gnuplot_figure.hpp"
#include "toolbox/assess/json_file.hpp"
#include "toolbox/assess/report_sections.hpp"

namespace ldv::assess {
namespace {

struct AllanTerms {
  double Q = 0, N = 0, B = 0, K = 0, R = 0, T_s = 0;
  bool gauss_markov = false;
};

// Allan variance of each term at tau (IEEE Std 952 forms; Gauss-Markov of std B and time constant T).
double avar_q(const AllanTerms& a, double tau) { return 3.0 * a.Q * a.Q / (tau * tau); }
double avar_n(const AllanTerms& a, double tau) { return a.N * a.N / tau; }
double avar_b(const AllanTerms& a, double tau) {
  if (!a.gauss_markov || a.T_s <= 0) return 2.0 * std::log(2.0) / M_PI * a.B * a.B;
  const double T = a.T_s, x = tau / T, qc = 2.0 * a.B * a.B / T;
  return qc * T * T / tau * (1.0 - (3.0 - 4.0 * std::exp(-x) + std::exp(-2.0 * x)) / (2.0 * x));
}
double avar_k(const AllanTerms& a, double tau) { return a.K * a.K * tau / 3.0; }
double avar_r(const AllanTerms& a, double tau) { return a.R * a.R * tau * tau / 2.0; }

}  // namespace

void add_allan_section(HtmlPage& page, const std::string& dir, const ReportInputs& in) {
  const YAML::Node j = load_json_object(in.allan_json, {"channels"}, "`ldv allan --json`");
  page.section("Allan deviation with the fitted noise terms");
  // The bars are the intervals `ldv allan` computed, at the confidence it states (its default: 68.3 %, one sigma).
  char bars[64] = "bars: intervals";
  if (const double confidence = json_double(j["confidence"], NAN); std::isfinite(confidence))
    std::snprintf(bars, sizeof bars, "bars: %.1f %% intervals", 100.0 * confidence);
  int ch = 0;
  for (const auto& c : j["channels"]) {
    const std::string name = c["name"] ? c["name"].as<std::string>() : "channel " + std::to_string(ch);
    const std::string unit = c["unit"] ? c["unit"].as<std::string>() : "";
    const auto tau = json_doubles(c["taus_s"]), dev = json_doubles(c["oadev"]);
    auto lo = json_doubles(c["oadev_lo"]), hi = json_doubles(c["oadev_hi"]);
    if (tau.empty() || tau.size() != dev.size()) continue;
    if (lo.size() != tau.size()) lo = dev;
    if (hi.size() != tau.size()) hi = dev;
    AllanTerms a;
    a.Q = json_double(c["Q"], 0), a.N = json_double(c["N"], 0), a.B = json_double(c["B"], 0);
    a.K = json_double(c["K"], 0), a.R = json_double(c["R"], 0), a.T_s = json_double(c["B_T_s"], 0);
    a.gauss_markov = c["B_model"] && c["B_model"].as<std::string>() == "gauss_markov";
    const bool fitted = c["Q"] && !c["Q"].IsNull();
    std::vector<double> ft, total, q, n, b, k, r;
    for (int i = 0; i <= 100 && fitted; ++i) {
      const double t = tau.front() * std::pow(tau.back() / tau.front(), i / 100.0);
      ft.push_back(t);
      q.push_back(std::sqrt(avar_q(a, t))), n.push_back(std::sqrt(avar_n(a, t))), b.push_back(std::sqrt(avar_b(a, t)));
      k.push_back(std::sqrt(avar_k(a, t))), r.push_back(std::sqrt(avar_r(a, t)));
      total.push_back(std::sqrt(avar_q(a, t) + avar_n(a, t) + avar_b(a, t) + avar_k(a, t) + avar_r(a, t)));
    }
    GnuplotFigure fig(dir, "allan_" + std::to_string(ch++), 760, 480);
    const std::string m = fig.add_data({tau, dev, lo, hi});
    fig.add("set logscale xy\nset format y '10^{%L}'\nset format x '10^{%L}'\nset xlabel 'tau [s]'");
    fig.add("set ylabel " + plot::gnuplot_label("Allan deviation [" + unit + "]") + "\nset title " + plot::gnuplot_label(name));
    std::string plot = "plot '" + m + "' using 1:2:3:4 with yerrorbars pt 7 ps 0.5 lc rgb '#1f77b4' title 'measured'";
    if (fitted) {
      const std::string f = fig.add_data({ft, total, q, n, b, k, r});
      const char* names[5] = {"Q", "N", "B", "K", "R"};
      plot += ", '" + f + "' using 1:2 with lines lw 2 lc rgb '#000000' title 'fitted model'";
      for (int t = 0; t < 5; ++t)
        plot += ", '" + f + "' using 1:($" + std::to_string(3 + t) + ">0?$" + std::to_string(3 + t) +
                ":1/0) with lines dt 2 lw 1.2 lc " + std::to_string(t + 1) + " title '" + names[t] + "'";
    }
    // The term lines span decades: keep the axis on the measurement.
    double y_lo = 1e300, y_hi = 0;
    for (size_t i = 0; i < dev.size(); ++i) {
      if (std::isfinite(lo[i]) && lo[i] > 0) y_lo = std::min(y_lo, lo[i]);
      if (std::isfinite(hi[i])) y_hi = std::max(y_hi, hi[i]);
    }
    if (y_hi > 0 && y_lo < y_hi) fig.add("set yrange [" + std::to_string(y_lo / 3) + ":" + std::to_string(y_hi * 3) + "]");
    fig.add(plot);
    HtmlTable t{name + ": fitted terms", {"term", "value", "sigma", "unit"}, {}};
    if (const YAML::Node pu = c["paper_units"]; pu && pu.IsMap()) {
      for (const char* term : {"Q", "N", "B", "K", "R"}) {
        const YAML::Node e = pu[term];
        if (!e) continue;
        t.rows.push_back({term, fixed(json_double(e["value"], NAN), 4), fixed(json_double(e["sigma"], NAN), 4),
                          e["unit"] ? e["unit"].as<std::string>() : ""});
      }
    }
    if (a.gauss_markov) t.rows.push_back({"B time constant", fixed(a.T_s, 1), "", "s"});
    page.figure(fig.render(), name + ": overlapping Allan deviation (" + bars + ") and the fitted terms",
                t.rows.empty() ? std::vector<HtmlTable>{} : std::vector<HtmlTable>{t});
  }
}

}  // namespace ldv::assess
