// Report sections on the solution itself: trajectory map, errors (or differences) with the filter's
// 3-sigma envelopes, and the paper's Tables 10-11 beside them.
#include <algorithm>
#include <cstdio>

#include "common/geo/earth_model.hpp"
#include "common/plot/gnuplot.hpp"
#include "toolbox/assess/gnuplot_figure.hpp"
#include "toolbox/assess/nav_difference.hpp"
#include "toolbox/assess/nav_side_files.hpp"
#include "toolbox/assess/report_sections.hpp"
#include "toolbox/assess/solution_comparison.hpp"

namespace ldv::assess {
namespace {

// East/north [m] of each thinned sample relative to `origin`.
void local_en(const NavSeries& s, const Geodetic& origin, size_t max_points, std::vector<double>& e, std::vector<double>& n) {
  for (size_t i : thin_indices(s.size(), max_points)) {
    const Vec3 d = earth::ned_between(origin, s.samples()[i].pos);
    n.push_back(d.x());
    e.push_back(d.y());
  }
}

HtmlTable comparison_table(const ComparisonResult& r, const std::string& title) {
  HtmlTable t;
  t.caption = title + " (" + std::to_string(r.epochs) + " epochs" +
              (r.matched_by_seconds_of_week ? "; " + r.matching_note() : std::string()) + ")";
  t.header = {"component", "unit", "mean", "std", "RMS", "max |d|"};
  for (int i = 0; i < kComponents; ++i) {
    const int dec = i < 6 ? 3 : 4;
    const ComponentStats& s = r.stats[i];
    t.rows.push_back({kComponentNames[i], kComponentUnits[i], fixed(s.mean, dec), fixed(s.std, dec), fixed(s.rms, dec),
                      fixed(s.max_abs, dec)});
  }
  return t;
}

}  // namespace

void add_trajectory_section(HtmlPage& page, const std::string& dir, const NavSeries& nav, const NavSeries* ref,
                            const ReportInputs& in) {
  page.section("Trajectory");
  const Geodetic origin = nav.samples().front().pos;
  GnuplotFigure fig(dir, "trajectory", 900, 640);
  std::vector<double> e, n;
  local_en(nav, origin, in.max_plot_points, e, n);
  const std::string sol = fig.add_data({e, n});
  std::string plot = "plot '" + sol + "' using 1:2 with lines lw 1.5 lc rgb '#1f77b4' title 'solution'";
  if (ref) {
    std::vector<double> re, rn;
    local_en(*ref, origin, in.max_plot_points, re, rn);
    plot += ", '" + fig.add_data({re, rn}) + "' using 1:2 with lines lw 1 dt 2 lc rgb '#d62728' title " + plot::gnuplot_label(in.reference_label);
  }
  plot += ", '" + fig.add_data({{e.front()}, {n.front()}}) + "' using 1:2 with points pt 7 ps 1.5 lc rgb '#2ca02c' title 'start'";
  fig.add("set size ratio -1\nset xlabel 'east [m]'\nset ylabel 'north [m]'\nset title 'Trajectory (local east/north from the first epoch)'");
  fig.add(plot);
  const double duration = nav.t_end_s() - nav.t_begin_s();
  double path_m = 0.0;
  for (size_t i = 1; i < nav.size(); ++i)
    path_m += earth::ned_between(nav.samples()[i - 1].pos, nav.samples()[i].pos).head<2>().norm();
  HtmlTable t{"Run", {"quantity", "value"}, {}};
  t.rows = {{"epochs", std::to_string(nav.size())},
            {"duration [s]", fixed(duration, 1)},
            {"path length [m]", fixed(path_m, 1)},
            {"mean speed [m/s]", fixed(duration > 0 ? path_m / duration : 0.0, 2)}};
  page.figure(fig.render(), "Trajectory: the solution" + std::string(ref ? " and " + in.reference_label : ""), {t});
}

void add_error_section(HtmlPage& page, const std::string& dir, const NavSeries& nav, const NavSeries* ref,
                       const ReportInputs& in) {
  std::vector<StdRow> sd;
  if (!in.std_file.empty()) sd = read_std_file(in.std_file);
  if (!ref && sd.empty()) return;
  page.section(ref ? "Errors against " + in.reference_label + " with the filter's 3-sigma envelope"
                   : "Filter 3-sigma envelope (no reference given)");
  const double t0 = nav.t_begin_s();
  // Differences at thinned solution epochs after the settling time.
  std::vector<double> t;
  std::array<std::vector<double>, kComponents> c;
  if (ref) {
    for (size_t i : thin_indices(nav.size(), in.max_plot_points)) {
      const NavSample& s = nav.samples()[i];
      if (s.t_s < t0 + in.settle_s) continue;
      const auto r = ref->at(s.t_s);
      if (!r) continue;
      const auto d = table_components(nav_difference(s, *r));
      t.push_back(s.t_s - t0);
      for (int k = 0; k < kComponents; ++k) c[k].push_back(d[k]);
    }
  }
  std::vector<double> st;
  std::array<std::vector<double>, 9> s3;  // 3 sigma: pos N E D, vel N E D, att r p y
  for (size_t i : thin_indices(sd.size(), in.max_plot_points)) {
    if (sd[i].t_s < t0 + in.settle_s) continue;
    st.push_back(sd[i].t_s - t0);
    for (int k = 0; k < 3; ++k) {
      s3[k].push_back(3 * sd[i].pos_ned_m(k));
      s3[3 + k].push_back(3 * sd[i].vel_ned_mps(k));
      s3[6 + k].push_back(3 * sd[i].att_deg(k));
    }
  }
  struct Panel {
    const char* stem;
    const char* title;
    const char* unit;
    std::array<int, 3> comp;   // table components plotted (E N D / vE vN vD / r p y)
    std::array<int, 3> sigma;  // the matching 3-sigma columns (N E D order in the std file)
  };
  const Panel panels[3] = {{"error_position", "Position", "m", {1, 0, 2}, {0, 1, 2}},
                           {"error_velocity", "Velocity", "m/s", {4, 3, 5}, {3, 4, 5}},
                           {"error_attitude", "Attitude", "deg", {6, 7, 8}, {6, 7, 8}}};
  const char* axis_names[3][3] = {{"north", "east", "down"}, {"north", "east", "down"}, {"roll", "pitch", "yaw"}};
  std::vector<HtmlTable> tables;
  if (ref) {
    const ComparisonResult r = compare_solutions(nav, *ref, {in.settle_s, 1.5});
    if (r.matched_by_seconds_of_week)  // said in the terminal too: a user may have meant another week
      std::fprintf(stderr, "ldv report: the solution and %s %s\n", in.reference_label.c_str(),
                   r.matching_note().c_str());
    tables.push_back(comparison_table(r, "Solution minus " + in.reference_label));
  }
  for (int p = 0; p < 3; ++p) {
    const Panel& P = panels[p];
    GnuplotFigure fig(dir, P.stem, 1000, 620);
    fig.add("set multiplot layout 3,1 title '" + std::string(P.title) + (ref ? " error" : " 3-sigma") + " [" + P.unit + "]'");
    fig.add("set lmargin 12\nset rmargin 22");
    const std::string ed = ref ? fig.add_data({t, c[P.comp[0]], c[P.comp[1]], c[P.comp[2]]}) : "";
    const std::string sdd = st.empty() ? "" : fig.add_data({st, s3[P.sigma[0]], s3[P.sigma[1]], s3[P.sigma[2]]});
    for (int k = 0; k < 3; ++k) {
      fig.add(std::string("set ylabel '") + axis_names[p][k] + " [" + P.unit + "]'");
      fig.add(k == 2 ? "set xlabel 'time since start [s]'" : "unset xlabel");
      std::string plot = "plot ";
      if (ref) plot += "'" + ed + "' using 1:" + std::to_string(2 + k) + " with lines lc rgb '#1f77b4' title 'error'";
      if (!sdd.empty()) {
        const std::string col = std::to_string(2 + k);
        plot += std::string(ref ? ", " : "") + "'" + sdd + "' using 1:" + col + " with lines lw 0.8 lc rgb '#d62728' title '+3 sigma', '" +
                sdd + "' using 1:(-$" + col + ") with lines lw 0.8 lc rgb '#d62728' title '-3 sigma'";
      }
      fig.add(plot);
    }
    fig.add("unset multiplot");
    page.figure(fig.render(), std::string(P.title) + (ref ? " error (solution minus " + in.reference_label + ")" : " 3-sigma") +
                                  (sdd.empty() ? "" : " with the filter's 3-sigma envelope"),
                p == 0 ? tables : std::vector<HtmlTable>{});
  }
}

}  // namespace ldv::assess
