// Report section: the stochastic model loop over `ldv allan --json` runs of one record with growing term
// sets (e.g. --terms QNBK, then QNBKR). Each run's misfit per decade (chi2 per point of the Allan curve
// against the fitted model) names the excluded term whose addition would lower it most; the next run adds
// it, and the misfit falls where the term lives. The section shows that per channel: the terms of each step,
// its misfit per decade with the term it names, and the fall.
#include <algorithm>
#include <cmath>

#include "common/plot/gnuplot.hpp"
#include "toolbox/assess/gnuplot_figure.hpp"
#include "toolbox/assess/json_file.hpp"
#include "toolbox/assess/report_sections.hpp"

namespace ldv::assess {
namespace {

struct Decade {
  double tau_lo_s = 0, tau_hi_s = 0, chi2_per_point = 0, chi2_with_term = 0;
  std::string closing_term;
};

struct Step {
  std::string file, terms;  // terms fitted, e.g. "QNBK"
  std::vector<Decade> decades;
};

std::string terms_of(const YAML::Node& c) {
  std::string t;
  for (const char* term : {"Q", "N", "B", "K", "R"}) {
    const YAML::Node m = c[std::string(term) + "_modelled"];
    if (m && m.as<bool>()) t += term;
  }
  return t;
}

// A decade the model does not fit: chi2 per point above this (about 3 % by chance with 10 points).
constexpr double kMisfitChi2PerPoint = 2.0;

bool misfit_named(const Decade& d) { return !d.closing_term.empty() && d.chi2_per_point > kMisfitChi2PerPoint; }

// The term the step's misfits name most often ("" none) and in how many decades.
std::pair<std::string, int> named_term(const Step& s) {
  std::string best;
  int best_count = 0;
  for (const Decade& d : s.decades) {
    if (!misfit_named(d)) continue;
    const int n = static_cast<int>(std::count_if(s.decades.begin(), s.decades.end(), [&](const Decade& e) {
      return misfit_named(e) && e.closing_term == d.closing_term;
    }));
    if (n > best_count) best = d.closing_term, best_count = n;
  }
  return {best, best_count};
}

}  // namespace

void add_stochastic_loop_section(HtmlPage& page, const std::string& dir, const ReportInputs& in) {
  // Channel name -> its steps, in the order the files were given.
  std::vector<std::string> channel_names;
  std::vector<std::vector<Step>> channels;
  for (const std::string& file : in.allan_loop_json) {
    const YAML::Node j = load_json_object(file, {"channels"}, "`ldv allan --json`");
    for (const auto& c : j["channels"]) {
      if (!c["name"] || !c["misfit"]) continue;
      const std::string name = c["name"].as<std::string>();
      auto it = std::find(channel_names.begin(), channel_names.end(), name);
      if (it == channel_names.end()) {
        channel_names.push_back(name);
        channels.emplace_back();
        it = channel_names.end() - 1;
      }
      Step s{file, terms_of(c), {}};
      for (const auto& m : c["misfit"]) {
        Decade d;
        d.tau_lo_s = json_double(m["tau_lo_s"], NAN), d.tau_hi_s = json_double(m["tau_hi_s"], NAN);
        d.chi2_per_point = json_double(m["chi2_per_point"], NAN);
        d.chi2_with_term = json_double(m["chi2_per_point_with_term"], NAN);
        if (m["closing_term"] && !m["closing_term"].IsNull()) d.closing_term = m["closing_term"].as<std::string>();
        s.decades.push_back(d);
      }
      channels[it - channel_names.begin()].push_back(s);
    }
  }
  page.section("Stochastic model loop: the misfit names the missing term, adding it makes the misfit fall");
  page.paragraph("Each step is one `ldv allan` run of the same record (" + std::to_string(in.allan_loop_json.size()) +
                 " runs, in the order given). Per decade of tau: chi2 per point of the Allan curve against the "
                 "step's fitted model (about 1 when the model fits) and the excluded term whose addition lowers it "
                 "most, with chi2 per point after adding it. A decade whose chi2 per point is above " +
                 fixed(kMisfitChi2PerPoint, 0) + " is not fitted; the term named there is the one to add.");
  for (size_t ch = 0; ch < channels.size(); ++ch) {
    const std::vector<Step>& steps = channels[ch];
    if (steps.empty() || steps.front().decades.empty()) continue;
    GnuplotFigure fig(dir, "stochastic_loop_" + std::to_string(ch), 760, 420);
    fig.add(
        "set logscale xy\nset format x '10^{%L}'\nset xlabel 'tau (decade centre) [s]'\nset ylabel 'chi2 per point'");
    fig.add("set title " + plot::gnuplot_label(channel_names[ch]) + "\nset key top left");
    std::string plot = "plot 1 with lines dt 2 lc rgb '#888888' title 'model fits (1)'";
    for (size_t k = 0; k < steps.size(); ++k) {
      std::vector<double> tau, chi2;
      for (const Decade& d : steps[k].decades) {
        if (!(d.chi2_per_point > 0) || !(d.tau_lo_s > 0)) continue;
        tau.push_back(std::sqrt(d.tau_lo_s * d.tau_hi_s));
        chi2.push_back(d.chi2_per_point);
      }
      if (tau.empty()) continue;
      const std::string f = fig.add_data({tau, chi2});
      plot += ", '" + f + "' using 1:2 with linespoints pt 7 lw 2 title " +
              plot::gnuplot_label("step " + std::to_string(k + 1) + ": " + steps[k].terms);
    }
    fig.add(plot);
    HtmlTable t{channel_names[ch] + ": chi2 per point per decade, step by step", {"tau [s]"}, {}};
    for (size_t k = 0; k < steps.size(); ++k)
      t.header.push_back("step " + std::to_string(k + 1) + " (" + steps[k].terms + ")");
    for (size_t i = 0; i < steps.front().decades.size(); ++i) {
      const Decade& d0 = steps.front().decades[i];
      std::vector<std::string> row{fixed(d0.tau_lo_s, 3) + " .. " + fixed(d0.tau_hi_s, 3)};
      for (const Step& s : steps) {
        if (i >= s.decades.size()) {
          row.push_back("");
          continue;
        }
        const Decade& d = s.decades[i];
        std::string cell = fixed(d.chi2_per_point, 3);
        if (!d.closing_term.empty()) cell += " (add " + d.closing_term + ": " + fixed(d.chi2_with_term, 3) + ")";
        row.push_back(cell);
      }
      t.rows.push_back(row);
    }
    page.figure(fig.render(), channel_names[ch] + ": the misfit per decade of each step", {t});
    for (size_t k = 0; k + 1 < steps.size(); ++k) {
      const auto [term, decades] = named_term(steps[k]);
      if (term.empty()) continue;
      const bool added =
          steps[k + 1].terms.find(term) != std::string::npos && steps[k].terms.find(term) == std::string::npos;
      double before = 0, after = 0;
      for (size_t i = 0; i < steps[k].decades.size() && i < steps[k + 1].decades.size(); ++i) {
        if (!misfit_named(steps[k].decades[i]) || steps[k].decades[i].closing_term != term) continue;
        before = std::max(before, steps[k].decades[i].chi2_per_point);
        after = std::max(after, steps[k + 1].decades[i].chi2_per_point);
      }
      page.paragraph(
          channel_names[ch] + ": step " + std::to_string(k + 1) + " does not fit " + std::to_string(decades) +
          " decade(s) (chi2 per point above " + fixed(kMisfitChi2PerPoint, 0) + ") and names " + term + " there; " +
          (added ? "step " + std::to_string(k + 2) + " adds it: the largest chi2 per point there falls from " +
                       fixed(before, 3) + " to " + fixed(after, 3) + "."
                 : "step " + std::to_string(k + 2) + " does not add it."));
    }
  }
}

}  // namespace ldv::assess
