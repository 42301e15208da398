// Report section: every sensor's innovations (GNSS, ZUPT, the aids) against their predicted 3-sigma, and NIS
// statistics. The innovations file has three columns whatever the sensor; rows a sensor does not have are 0.
#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "common/plot/gnuplot.hpp"
#include "toolbox/assess/gnuplot_figure.hpp"
#include "toolbox/assess/nav_side_files.hpp"
#include "toolbox/assess/report_sections.hpp"

namespace ldv::assess {
namespace {

// What each row of a sensor's innovation is (estimator/filter/records.hpp) and its unit.
struct RowLabels {
  std::vector<std::string> names;
  std::string unit;
};
RowLabels row_labels(const std::string& sensor) {
  if (sensor == "gnss_position") return {{"north", "east", "down"}, "m"};
  if (sensor == "zaru") return {{"x", "y", "z"}, "rad/s"};
  if (sensor == "nhc") return {{"lateral", "vertical"}, "m/s"};
  if (sensor == "odometer") return {{"forward"}, "m/s"};
  return {{"north", "east", "down"}, "m/s"};  // gnss_velocity, zupt
}

}  // namespace

void add_innovation_section(HtmlPage& page, const std::string& dir, const ReportInputs& in) {
  const std::vector<InnovationRow> rows = read_innovations_file(in.innovations);
  if (rows.empty()) return;
  page.section("Innovations (predicted minus measured) with their 3-sigma");
  std::map<std::string, std::vector<const InnovationRow*>> by_kind;
  for (const auto& r : rows) by_kind[r.kind].push_back(&r);
  const double t0 = rows.front().t_s;
  HtmlTable stats{"NIS per measurement (mean = the measurement's rows when consistent)",
                  {"measurement", "count", "accepted %", "mean NIS", "RMS row 1", "RMS row 2", "RMS row 3"},
                  {}};
  for (const auto& [kind, list] : by_kind) {
    double nis = 0, accepted = 0;
    Vec3 sq = Vec3::Zero();
    for (const auto* r : list) {
      nis += r->nis;
      accepted += r->accepted;
      sq += r->innovation.cwiseAbs2();
    }
    const double n = static_cast<double>(list.size());
    const Vec3 rms = (sq / n).cwiseSqrt();
    const RowLabels labels = row_labels(kind);
    std::vector<std::string> row = {kind, std::to_string(list.size()), fixed(100 * accepted / n, 1), fixed(nis / n, 2)};
    for (size_t k = 0; k < 3; ++k)
      row.push_back(k < labels.names.size()
                        ? labels.names[k] + " " + fixed(rms(static_cast<int>(k)), 4) + " " + labels.unit
                        : std::string("-"));
    stats.rows.push_back(row);
  }
  // A robust half range per row: the 99th percentile of |innovation| and the 95th of the 3-sigma envelope, with room;
  // one start-up 3-sigma of metres made 2 cm innovations a flat line (issue 52). What lies beyond is counted.
  const auto quantile = [](std::vector<double> v, double q) {
    std::erase_if(v, [](double x) { return !std::isfinite(x); });  // the NaN rows that break lines at gaps
    if (v.empty()) return 0.0;
    const auto at = v.begin() + static_cast<long>(q * static_cast<double>(v.size() - 1));
    std::nth_element(v.begin(), at, v.end());
    return *at;
  };
  bool first = true;
  for (const auto& [kind, list] : by_kind) {
    std::vector<double> t, i0, i1, i2, s0, s1, s2;
    // A gap in the measurements (an outage) breaks the envelope's line: a row of NaN, which gnuplot leaves undrawn.
    std::vector<double> steps;
    for (size_t k = 1; k < list.size(); ++k) steps.push_back(list[k]->t_s - list[k - 1]->t_s);
    const double thinning =
        std::max(1.0, static_cast<double>(list.size()) / std::max(1.0, static_cast<double>(in.max_plot_points)));
    const double gap_s = 5.0 * thinning * std::max(quantile(steps, 0.5), 1e-3);
    for (size_t k : thin_indices(list.size(), static_cast<size_t>(in.max_plot_points))) {
      const InnovationRow& r = *list[k];
      if (!t.empty() && r.t_s - t0 - t.back() > gap_s)
        for (std::vector<double>* column : {&t, &i0, &i1, &i2, &s0, &s1, &s2}) column->push_back(NAN);
      t.push_back(r.t_s - t0);
      i0.push_back(r.innovation(0)), i1.push_back(r.innovation(1)), i2.push_back(r.innovation(2));
      s0.push_back(3 * r.sqrt_S(0)), s1.push_back(3 * r.sqrt_S(1)), s2.push_back(3 * r.sqrt_S(2));
    }
    const RowLabels labels = row_labels(kind);
    const int rows = static_cast<int>(labels.names.size());
    GnuplotFigure fig(dir, "innovations_" + kind, 1000, 200 * rows);
    const std::string d = fig.add_data({t, i0, i1, i2, s0, s1, s2});
    fig.add("set multiplot layout " + std::to_string(rows) + ",1 title " +
            plot::gnuplot_label(kind + " innovations [" + labels.unit + "]") + "\nset lmargin 12\nset rmargin 22");
    const std::vector<double>* innovations[3] = {&i0, &i1, &i2};
    const std::vector<double>* sigmas[3] = {&s0, &s1, &s2};
    long beyond = 0;
    for (int k = 0; k < rows; ++k) {
      const std::string c = std::to_string(2 + k), s = std::to_string(5 + k);
      std::vector<double> magnitude;
      for (double v : *innovations[k]) magnitude.push_back(std::abs(v));
      const double half = 1.3 * std::max(quantile(magnitude, 0.99), quantile(*sigmas[k], 0.95));
      if (half > 0 && std::isfinite(half)) {
        fig.add("set yrange [" + std::to_string(-half) + ":" + std::to_string(half) + "]");
        for (double v : magnitude) beyond += std::isfinite(v) && v > half;
      }
      fig.add("set ylabel " + plot::gnuplot_label(labels.names[k] + " [" + labels.unit + "]"));
      fig.add(k == rows - 1 ? "set xlabel 'time since first measurement [s]'" : "unset xlabel");
      fig.add("plot '" + d + "' using 1:" + c + " with points pt 7 ps 0.3 lc rgb '#1f77b4' title 'innovation', '" + d +
              "' using 1:" + s + " with lines lw 0.8 lc rgb '#d62728' title '+3 sqrt(S)', '" + d + "' using 1:(-$" + s +
              ") with lines lw 0.8 lc rgb '#d62728' title '-3 sqrt(S)'");
    }
    fig.add("unset multiplot");
    page.figure(fig.render(),
                kind + " innovations and their predicted 3-sigma" +
                    (beyond > 0 ? " (" + std::to_string(beyond) + " values beyond the plotted range, which covers 99 %)"
                                : std::string()),
                first ? std::vector<HtmlTable>{stats} : std::vector<HtmlTable>{});
    first = false;
  }
}

}  // namespace ldv::assess
