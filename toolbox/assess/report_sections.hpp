#pragma once
// `ldv report`: one function per section of the page; each writes its PNGs (gnuplot) into `dir` and
// appends its plots and tables to the page. Sections whose input is missing are not called.
#include <string>
#include <vector>

#include "toolbox/assess/html_page.hpp"
#include "toolbox/assess/nav_series.hpp"

namespace ldv::assess {

struct ReportInputs {
  std::string title = "ldvnav run report";
  std::string nav;          // the solution (.nav)
  std::string truth;        // truth or a reference solution (.nav), optional
  std::string reference_label = "truth";
  std::string std_file;     // ldv nav's _std.txt (default: beside the .nav when present)
  std::string innovations;  // ldv nav's _innovations.txt (default: beside the .nav when present)
  // ldv smooth's forward solution and separation (default: FILE_forward.nav, FILE_separation.txt when present)
  std::string forward, separation;
  std::string outage_json, allan_json, diagnose_json;
  // `ldv allan --json` runs of one record with growing term sets, in order: the stochastic model loop
  std::vector<std::string> allan_loop_json;
  double settle_s = 0.0;
  int max_plot_points = 4000;
};

void add_trajectory_section(HtmlPage& page, const std::string& dir, const NavSeries& nav, const NavSeries* reference,
                            const ReportInputs& in);
void add_error_section(HtmlPage& page, const std::string& dir, const NavSeries& nav, const NavSeries* reference,
                       const ReportInputs& in);
void add_smoothing_section(HtmlPage& page, const std::string& dir, const NavSeries& smoothed, const NavSeries* reference,
                           const ReportInputs& in);
void add_innovation_section(HtmlPage& page, const std::string& dir, const ReportInputs& in);
void add_outage_section(HtmlPage& page, const std::string& dir, const ReportInputs& in);
void add_allan_section(HtmlPage& page, const std::string& dir, const ReportInputs& in);
void add_stochastic_loop_section(HtmlPage& page, const std::string& dir, const ReportInputs& in);
void add_diagnosis_section(HtmlPage& page, const std::string& dir, const ReportInputs& in);

// Writes dir/index.html and its PNGs; returns the path of index.html.
std::string write_report(const ReportInputs& in, const std::string& dir);

}  // namespace ldv::assess
