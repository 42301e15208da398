// Report section of a smoothed run (`ldv smooth`): smoothed against forward error (with a reference), and the
// separation (forward minus smoothed) inside its expected 3-sigma envelope sqrt(P forward - P smoothed), the
// QC Inertial Explorer users read: where the separation leaves its envelope, the model does not hold.
#include <cmath>

#include "common/formats/kfgins_files.hpp"
#include "toolbox/assess/gnuplot_figure.hpp"
#include "toolbox/assess/nav_difference.hpp"
#include "toolbox/assess/nav_side_files.hpp"
#include "toolbox/assess/report_sections.hpp"
#include "toolbox/assess/solution_comparison.hpp"

namespace ldv::assess {
namespace {

// Horizontal error and |down| of a solution against the reference at thinned epochs after the settling time.
struct ErrorTrace {
  std::vector<double> t, horizontal, down;
};
ErrorTrace error_trace(const NavSeries& nav, const NavSeries& ref, const ReportInputs& in, double t0) {
  ErrorTrace e;
  for (size_t i : thin_indices(nav.size(), in.max_plot_points)) {
    const NavSample& s = nav.samples()[i];
    if (s.t_s < t0 + in.settle_s) continue;
    const auto r = ref.at(s.t_s);
    if (!r) continue;
    const NavDifference d = nav_difference(s, *r);
    e.t.push_back(s.t_s - t0);
    e.horizontal.push_back(d.pos_ned_m.head<2>().norm());
    e.down.push_back(d.pos_ned_m.z());
  }
  return e;
}

}  // namespace

void add_smoothing_section(HtmlPage& page, const std::string& dir, const NavSeries& smoothed, const NavSeries* ref,
                           const ReportInputs& in) {
  page.section("Smoothing: forward and smoothed solutions, and their separation");
  const double t0 = smoothed.t_begin_s();
  if (ref && !in.forward.empty()) {
    const NavSeries forward = NavSeries::from_records(read_nav(in.forward));
    const ComparisonOptions co{in.settle_s, 1.5};
    const ComparisonResult cf = compare_solutions(forward, *ref, co), cs = compare_solutions(smoothed, *ref, co);
    HtmlTable t;
    t.caption = "RMS and largest error against " + in.reference_label + ": forward / smoothed";
    t.header = {"component", "unit", "forward RMS", "smoothed RMS", "forward max", "smoothed max"};
    for (int i = 0; i < kComponents; ++i) {
      const int dec = i < 6 ? 3 : 4;
      t.rows.push_back({kComponentNames[i], kComponentUnits[i], fixed(cf.stats[i].rms, dec),
                        fixed(cs.stats[i].rms, dec), fixed(cf.stats[i].max_abs, dec), fixed(cs.stats[i].max_abs, dec)});
    }
    const ErrorTrace ef = error_trace(forward, *ref, in, t0), es = error_trace(smoothed, *ref, in, t0);
    GnuplotFigure fig(dir, "smoothing_error", 1000, 560);
    fig.add("set multiplot layout 2,1 title 'Error against the reference: forward filter and smoother'");
    fig.add("set lmargin 12\nset rmargin 22\nset logscale y\nset ylabel 'horizontal [m]'\nunset xlabel");
    const std::string df = fig.add_data({ef.t, ef.horizontal, ef.down}),
                      ds = fig.add_data({es.t, es.horizontal, es.down});
    fig.add("plot '" + df + "' using 1:($2 > 1e-4 ? $2 : 1e-4) with lines lc rgb '#d62728' title 'forward', '" + ds +
            "' using 1:($2 > 1e-4 ? $2 : 1e-4) with lines lc rgb '#1f77b4' title 'smoothed'");
    fig.add("unset logscale y\nset ylabel 'down [m]'\nset xlabel 'time since start [s]'");
    fig.add("plot '" + df + "' using 1:3 with lines lc rgb '#d62728' title 'forward', '" + ds +
            "' using 1:3 with lines lc rgb '#1f77b4' title 'smoothed'");
    fig.add("unset multiplot");
    page.figure(fig.render(),
                "Forward and smoothed error (horizontal on a log scale): the smoother ties both ends "
                "of each GNSS gap, where the forward filter drifts",
                {t});
  }
  if (in.separation.empty()) return;
  const std::vector<SeparationRow> sep = read_separation_file(in.separation);
  if (sep.empty()) return;
  std::vector<double> t;
  std::array<std::vector<double>, 3> c;  // separation / its expected sigma, N E D
  long inside = 0, total = 0;
  for (const SeparationRow& r : sep) {
    if (r.t_s < t0 + in.settle_s) continue;
    for (int k = 0; k < 3; ++k) {
      if (r.std(k) <= 1e-4) continue;  // no separation expected (the run's end, a restart): nothing to check
      inside += std::abs(r.separation(k)) <= 3.0 * r.std(k);
      ++total;
    }
  }
  for (size_t i : thin_indices(sep.size(), in.max_plot_points)) {
    if (sep[i].t_s < t0 + in.settle_s) continue;
    t.push_back(sep[i].t_s - t0);
    for (int k = 0; k < 3; ++k) c[k].push_back(sep[i].std(k) > 1e-4 ? sep[i].separation(k) / sep[i].std(k) : 0.0);
  }
  GnuplotFigure fig(dir, "smoothing_separation", 1000, 620);
  fig.add(
      "set multiplot layout 3,1 title 'Separation (forward minus smoothed position) in units of its expected sigma'");
  fig.add("set lmargin 12\nset rmargin 22\nset yrange [-5:5]");
  const std::string d = fig.add_data({t, c[0], c[1], c[2]});
  const char* names[3] = {"north", "east", "down"};
  for (int k = 0; k < 3; ++k) {
    fig.add(std::string("set ylabel '") + names[k] + " [sigma]'");
    fig.add(k == 2 ? "set xlabel 'time since start [s]'" : "unset xlabel");
    fig.add("plot '" + d + "' using 1:" + std::to_string(2 + k) +
            " with lines lc rgb '#1f77b4' title 'separation', 3 with lines lw 0.8 lc rgb '#d62728' title '+-3 sigma', "
            "-3 with lines lw 0.8 lc rgb '#d62728' notitle");
  }
  fig.add("unset multiplot");
  HtmlTable qc{"Separation QC", {"quantity", "value"}, {}};
  qc.rows = {{"rows", std::to_string(sep.size())},
             {"position components inside 3 sigma", fixed(total > 0 ? 100.0 * inside / total : 0.0, 2) + " %"},
             {"expected for a consistent model", "99.7 %"}};
  page.figure(fig.render(),
              "Separation of the forward and smoothed solutions, divided by its expected 1-sigma sqrt(P forward - P "
              "smoothed) (which opens inside GNSS gaps): beyond +-3 the model does not hold there",
              {qc});
}

}  // namespace ldv::assess
