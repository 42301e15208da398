// Report section: an `ldv diagnose --json` file (issue 6 schema: model, consistent, candidates
// [{effect, statistic, p_value, estimate, sigma, group}], verdict {add}; before/after when present).
#include <cmath>
#include <functional>
#include <map>

#include "toolbox/assess/gnuplot_figure.hpp"
#include "common/plot/gnuplot.hpp"
#include "toolbox/assess/json_file.hpp"
#include "toolbox/assess/report_sections.hpp"

namespace ldv::assess {
namespace {

std::string text_of(const YAML::Node& n) {
  if (!n) return "";
  if (n.IsScalar()) return n.as<std::string>();
  if (n.IsSequence()) {
    std::string s;
    for (const auto& x : n) s += (s.empty() ? "" : ", ") + text_of(x);
    return "[" + s + "]";
  }
  return "{...}";
}

// Numeric leaves of a JSON object as "a.b.c" -> value.
void numeric_leaves(const YAML::Node& n, const std::string& prefix, std::map<std::string, double>& out) {
  if (n.IsMap()) {
    for (const auto& kv : n) numeric_leaves(kv.second, prefix.empty() ? kv.first.as<std::string>() : prefix + "." + kv.first.as<std::string>(), out);
  } else if (n.IsScalar()) {
    const double v = json_double(n, NAN);
    if (std::isfinite(v)) out[prefix] = v;
  }
}

}  // namespace

void add_diagnosis_section(HtmlPage& page, const std::string& dir, const ReportInputs& in) {
  const YAML::Node j = load_json_object(in.diagnose_json, {"model", "candidates"}, "`ldv diagnose --json`");
  page.section("Diagnosis");
  page.paragraph("Model " + text_of(j["model"]) + "; consistent: " + text_of(j["consistent"]) +
                 "; verdict: add " + (j["verdict"] ? text_of(j["verdict"]["add"]) : std::string("-")) + ".");
  HtmlTable cand{"Candidate effects, best first", {"effect", "statistic", "p-value", "estimate", "sigma", "group"}, {}};
  std::vector<double> idx, stat;
  std::string labels;
  for (const auto& c : j["candidates"]) {
    cand.rows.push_back({text_of(c["effect"]), text_of(c["statistic"]), text_of(c["p_value"]), text_of(c["estimate"]),
                         text_of(c["sigma"]), text_of(c["group"])});
    const double s = json_double(c["statistic"], NAN);
    if (std::isfinite(s) && s > 0) {
      labels += std::string(labels.empty() ? "" : ", ") + plot::gnuplot_label(text_of(c["effect"])) + " " + std::to_string(idx.size());
      idx.push_back(static_cast<double>(idx.size()));
      stat.push_back(s);
    }
  }
  if (!idx.empty()) {
    GnuplotFigure fig(dir, "diagnosis_candidates", 900, 400);
    const std::string d = fig.add_data({idx, stat});
    fig.add("set style fill solid 0.7\nset boxwidth 0.6\nset logscale y\nset xtics rotate by -30 (" + labels + ")");
    fig.add("set ylabel 'test statistic'\nset title 'Candidate scores'\nset xrange [-0.5:" + std::to_string(idx.size() - 0.5) + "]");
    fig.add("plot '" + d + "' using 1:2 with boxes lc rgb '#1f77b4' notitle");
    page.figure(fig.render(), "Score of each candidate effect (higher: more evidence it is missing)", {cand});
  } else if (!cand.rows.empty()) {
    page.table(cand);
  }
  if (j["before"] && j["after"]) {
    std::map<std::string, double> before, after;
    numeric_leaves(j["before"], "", before);
    numeric_leaves(j["after"], "", after);
    HtmlTable t{"Before and after adding the verdict's effects", {"quantity", "before", "after", "after / before"}, {}};
    std::vector<double> x, b, a;
    std::string labels2;
    for (const auto& [k, v] : before) {
      const auto it = after.find(k);
      if (it == after.end()) continue;
      t.rows.push_back({k, fixed(v, 4), fixed(it->second, 4), v != 0 ? fixed(it->second / v, 3) : "-"});
      labels2 += std::string(labels2.empty() ? "" : ", ") + plot::gnuplot_label(k) + " " + std::to_string(x.size());
      x.push_back(static_cast<double>(x.size()));
      b.push_back(std::abs(v));
      a.push_back(std::abs(it->second));
    }
    if (!x.empty()) {
      GnuplotFigure fig(dir, "diagnosis_before_after", 900, 420);
      std::vector<double> xb, xa;
      for (double v : x) xb.push_back(v - 0.18), xa.push_back(v + 0.18);
      const std::string d = fig.add_data({xb, b, xa, a});
      fig.add("set style fill solid 0.7\nset boxwidth 0.35\nset logscale y\nset xtics rotate by -30 (" + labels2 + ")");
      fig.add("set xrange [-0.6:" + std::to_string(x.size() - 0.4) + "]\nset title 'Before / after (absolute values)'");
      fig.add("plot '" + d + "' using 1:2 with boxes lc rgb '#d62728' title 'before', '' using 3:4 with boxes lc rgb '#2ca02c' title 'after'");
      page.figure(fig.render(), "Before and after the diagnosis", {t});
    }
  }
}

}  // namespace ldv::assess
