// Report section: an `ldv diagnose --json` file (toolbox/diagnose/README.md, JSON): the verdict and whether the model
// then fits, the error against truth before and after, the step-by-step fall of the misfit, and the candidates in
// their units.
#include <cmath>
#include <cstdio>
#include <string>
#include <tuple>
#include <vector>

#include "common/plot/gnuplot.hpp"
#include "toolbox/assess/gnuplot_figure.hpp"
#include "toolbox/assess/json_file.hpp"
#include "toolbox/assess/report_sections.hpp"

namespace ldv::assess {
namespace {

std::string text_of(const YAML::Node& n) {
  if (!n || n.IsNull()) return "-";
  if (n.IsScalar()) return n.as<std::string>();
  if (n.IsSequence()) {
    std::string s;
    for (const auto& x : n) s += (s.empty() ? "" : ", ") + text_of(x);
    return s;
  }
  return "-";
}

// Four significant digits ("-" for a missing component: an axis the test left out).
std::string significant(double v) {
  if (!std::isfinite(v)) return "-";
  char b[32];
  std::snprintf(b, sizeof b, "%.4g", v);
  return b;
}

// A vector of SI values in the effect's print unit: "0.5026, -0.2962, -1.201".
std::string in_unit(const YAML::Node& values, double scale) {
  std::string s;
  if (!values || !values.IsSequence()) return "-";
  for (const auto& x : values) s += (s.empty() ? "" : ", ") + significant(json_double(x, NAN) * scale);
  return s;
}

struct PrintUnit {
  std::string unit;
  double scale = 1.0;
};
// The print unit of an effect as the candidates list states it; the noise factors are plain factors.
PrintUnit unit_of(const YAML::Node& j, const std::string& effect) {
  if (effect == "gnss_noise") return {"x the stated variance", 1.0};
  if (effect == "imu_noise") return {"x the PSD (gyro, accel)", 1.0};
  for (const auto& c : j["candidates"])
    if (text_of(c["effect"]) == effect) return {text_of(c["print_unit"]), json_double(c["print_scale"], 1.0)};
  return {"SI", 1.0};
}

}  // namespace

void add_diagnosis_section(HtmlPage& page, const std::string& dir, const ReportInputs& in) {
  const YAML::Node j = load_json_object(in.diagnose_json, {"model", "candidates"}, "`ldv diagnose --json`");
  page.section("Diagnosis");
  // The headline: what the verdict adds (effects, and the noise a step rescaled), and whether the model then fits.
  const YAML::Node verdict = j["verdict"];
  std::string adds = verdict && verdict["add"] && verdict["add"].size() > 0 ? text_of(verdict["add"]) : "";
  for (const auto& c : j["self_calibration"])
    if (c["applied"] && c["applied"].as<bool>() &&
        (text_of(c["name"]) == "gnss_noise" || text_of(c["name"]) == "imu_noise"))
      for (const auto& st : j["steps"])
        if (text_of(st["added"]) == text_of(c["name"]))
          adds += (adds.empty() ? "" : ", ") + text_of(c["name"]) + " rescaled";
  const bool consistent = j["consistent"] && j["consistent"].as<bool>();
  page.paragraph("Model " + text_of(j["model"]) + ". Verdict: " + (adds.empty() ? "nothing to add" : "add " + adds) +
                 ". " +
                 (consistent ? (adds.empty() ? "The model is consistent with the data."
                                             : "With it, the model is consistent with the data.")
                             : "The final model still does not fit the data (see its check below)."));
  // The error falling, against truth where the diagnosis had one.
  const YAML::Node truth = j["truth"];
  if (truth && truth["before"] && truth["after"] && truth["before"]["rms_pos_3d_m"]) {
    HtmlTable t{"Navigation error against truth, before and after (the tuned model)",
                {"quantity", "unit", "before", "after"},
                {}};
    for (const auto& [key, label, unit] :
         {std::tuple{"rms_pos_3d_m", "position RMS 3D", "m"}, std::tuple{"rms_horizontal_m", "horizontal RMS", "m"},
          std::tuple{"rms_vertical_m", "vertical RMS", "m"}, std::tuple{"max_horizontal_m", "max horizontal", "m"},
          std::tuple{"rms_yaw_deg", "yaw RMS", "deg"}})
      t.rows.push_back({label, unit, significant(json_double(truth["before"][key], NAN)),
                        significant(json_double(truth["after"][key], NAN))});
    page.table(t);
  }
  // Step by step: what each step added, its estimate in its unit, how the model then fits the GNSS positions.
  if (j["steps"] && j["steps"].size() > 0) {
    HtmlTable t{"Step by step (the GNSS position fit of each model)",
                {"step", "added", "estimate", "sigma", "unit", "fixes used", "mean NIS", "consistent"},
                {}};
    std::vector<double> x, nis;
    std::string labels;
    int k = 0;
    for (const auto& st : j["steps"]) {
      const std::string added = st["added"] && !st["added"].IsNull() ? text_of(st["added"]) : "(model under test)";
      const PrintUnit u = unit_of(j, added);
      const bool has = st["estimate"] && st["estimate"].IsSequence();
      t.rows.push_back({std::to_string(k), added, has ? in_unit(st["estimate"], u.scale) : "-",
                        has ? in_unit(st["sigma"], u.scale) : "-", has ? u.unit : "-",
                        text_of(st["accepted_fixes"]) + " / " + text_of(st["total_fixes"]),
                        significant(json_double(st["mean_nis"], NAN)), text_of(st["consistent"])});
      const double v = json_double(st["mean_nis"], NAN);
      if (std::isfinite(v) && v > 0) {
        labels += std::string(labels.empty() ? "" : ", ") + plot::gnuplot_label(added) + " " + std::to_string(x.size());
        x.push_back(static_cast<double>(x.size()));
        nis.push_back(v);
      }
      ++k;
    }
    if (x.size() > 1) {
      GnuplotFigure fig(dir, "diagnosis_steps", 900, 400);
      const std::string d = fig.add_data({x, nis});
      fig.add("set style fill solid 0.7\nset boxwidth 0.6\nset xtics rotate by -30 (" + labels + ")");
      fig.add(
          "set ylabel 'mean NIS of the GNSS positions'\nset title 'The misfit falling step by step (3: consistent)'");
      fig.add("set xrange [-0.5:" + std::to_string(x.size() - 0.5) + "]\nset yrange [0:*]");
      fig.add("plot '" + d +
              "' using 1:2 with boxes lc rgb '#1f77b4' notitle, 3 with lines dt 2 lc rgb '#333333' title 'expected'");
      page.figure(fig.render(), "Mean NIS of the GNSS positions after each step (3 for a consistent 3-D fix)", {t});
    } else {
      page.table(t);
    }
  }
  // The candidates as the first step screened them, in their units; an untestable one says so.
  HtmlTable cand{"Candidate effects, best first (score test at the model under test; reruns ordered them)",
                 {"effect", "statistic", "p-value", "estimate", "sigma", "unit", "cannot be told apart from"},
                 {}};
  std::vector<double> idx, stat;
  std::string labels;
  for (const auto& c : j["candidates"]) {
    const std::string effect = text_of(c["effect"]);
    const double scale = json_double(c["print_scale"], 1.0);
    const bool testable = !c["testable"] || c["testable"].as<bool>();
    std::string group;
    for (const auto& g : c["group"])
      if (text_of(g) != effect) group += (group.empty() ? "" : ", ") + text_of(g);
    cand.rows.push_back({effect, testable ? significant(json_double(c["statistic"], NAN)) : "untestable",
                         testable ? significant(json_double(c["p_value"], NAN)) : "-",
                         testable ? in_unit(c["estimate"], scale) : "-", testable ? in_unit(c["sigma"], scale) : "-",
                         text_of(c["print_unit"]), group.empty() ? "-" : group});
    const double s = json_double(c["statistic"], NAN);
    if (testable && std::isfinite(s) && s > 0) {
      labels +=
          std::string(labels.empty() ? "" : ", ") + plot::gnuplot_label(effect) + " " + std::to_string(idx.size());
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
}

}  // namespace ldv::assess
