// Report section: drift curves of the GNSS outages of an `ldv outage --json` file, with the filter's
// horizontal 3-sigma, and the Table 12 summary beside them.
#include <cmath>

#include "toolbox/assess/gnuplot_figure.hpp"
#include "toolbox/assess/json_file.hpp"
#include "toolbox/assess/report_sections.hpp"

namespace ldv::assess {

void add_outage_section(HtmlPage& page, const std::string& dir, const ReportInputs& in) {
  const YAML::Node j = load_json_object(in.outage_json, {"lengths", "outages"}, "`ldv outage --json`");
  const std::string reference = j["reference"] ? j["reference"].as<std::string>() : "reference";
  page.section("GNSS outages: drift against the " + reference);
  HtmlTable table{"Drift at the outage end (paper Table 12) and the KF-GINS metric",
                  {"outage [s]", "n", "mean hor [m]", "max hor [m]", "max |D| [m]", "max |yaw| [deg]", "RMS of max hor [m]",
                   "inside 3 sigma (pos)"},
                  {}};
  for (const auto& l : j["lengths"]) {
    const auto max_end = json_doubles(l["max_abs_end"]);
    table.rows.push_back({fixed(json_double(l["length_s"], NAN), 0), std::to_string(l["outages"].as<int>()),
                          fixed(json_double(l["mean_horizontal_end_m"], NAN), 3), fixed(json_double(l["max_horizontal_end_m"], NAN), 3),
                          max_end.size() == 9 ? fixed(max_end[2], 3) : "-", max_end.size() == 9 ? fixed(max_end[8], 4) : "-",
                          fixed(json_double(l["rms_max_horizontal_m"], NAN), 3),
                          fixed(100 * json_double(l["inside_3sigma_pos"], NAN), 0) + " %"});
  }
  bool first = true;
  for (const auto& l : j["lengths"]) {
    const double length = json_double(l["length_s"], NAN);
    GnuplotFigure fig(dir, "outage_drift_" + fixed(length, 0) + "s", 900, 420);
    std::string plot;
    int k = 0;
    for (const auto& o : j["outages"]) {
      if (json_double(o["length_s"], NAN) != length) continue;
      const YAML::Node c = o["curve"];
      const auto t = json_doubles(c["t_s"]), n = json_doubles(c["north_m"]), e = json_doubles(c["east_m"]);
      const auto sn = json_doubles(c["std_north_m"]), se = json_doubles(c["std_east_m"]);
      std::vector<double> h(t.size()), s3(t.size());
      for (size_t i = 0; i < t.size(); ++i) {
        h[i] = std::hypot(n[i], e[i]);
        s3[i] = 3.0 * std::hypot(sn[i], se[i]);
      }
      const std::string d = fig.add_data({t, h, s3});
      const std::string color = "lc " + std::to_string(k % 8 + 1);
      plot += std::string(plot.empty() ? "plot " : ", ") + "'" + d + "' using 1:2 with lines lw 1.5 " + color + " title 'start " +
              fixed(json_double(o["start_sow_s"], NAN), 0) + "', '" + d + "' using 1:3 with lines dt 2 " + color + " notitle";
      ++k;
    }
    if (plot.empty()) continue;
    fig.add("set title 'Horizontal drift during " + fixed(length, 0) + " s outages (dashed: filter 3 sigma)'");
    fig.add("set xlabel 'time since the outage start [s]'\nset ylabel 'horizontal drift [m]'");
    fig.add(plot);
    page.figure(fig.render(), "Horizontal drift of each " + fixed(length, 0) + " s outage against the " + reference +
                                  ", and the filter's horizontal 3-sigma (dashed)",
                first ? std::vector<HtmlTable>{table} : std::vector<HtmlTable>{});
    first = false;
  }
}

}  // namespace ldv::assess
