#include <filesystem>

#include "common/formats/kfgins_files.hpp"
#include "common/geo/earth_model.hpp"
#include "common/io/input_error.hpp"
#include "toolbox/assess/gnuplot_figure.hpp"
#include "toolbox/assess/nav_side_files.hpp"
#include "toolbox/assess/report_sections.hpp"

namespace ldv::assess {
namespace fs = std::filesystem;

namespace {
// A section built from another command's JSON: a file of the wrong shape (another command's JSON, a list where an
// object belongs) is refused naming the file and what it should be, not with yaml-cpp's "bad conversion".
template <typename Section>
void json_section(const std::string& path, const char* written_by, Section&& add) {
  try {
    add();
  } catch (const YAML::Exception& e) {
    throw InputError(path, e.mark.is_null() ? 0 : e.mark.line + 1,
                     std::string("expected the JSON that ") + written_by + " writes (" + e.msg + ")");
  }
}
}  // namespace

std::string write_report(const ReportInputs& given, const std::string& dir) {
  ReportInputs in = given;
  fs::create_directories(dir);
  HtmlPage page(in.title);
  if (!in.nav.empty()) {
    if (in.std_file.empty() && fs::exists(std_path_for(in.nav))) in.std_file = std_path_for(in.nav);
    if (in.innovations.empty() && fs::exists(innovations_path_for(in.nav))) in.innovations = innovations_path_for(in.nav);
    // A smoothed run (ldv smooth writes both the separation and the forward solution beside it); its
    // innovations are the forward run's.
    if (in.separation.empty() && fs::exists(separation_path_for(in.nav))) {
      in.separation = separation_path_for(in.nav);
      if (in.forward.empty() && fs::exists(forward_path_for(in.nav))) in.forward = forward_path_for(in.nav);
    }
    if (in.innovations.empty() && !in.forward.empty() && fs::exists(innovations_path_for(in.forward)))
      in.innovations = innovations_path_for(in.forward);
    const NavSeries nav = NavSeries::from_records(read_nav(in.nav));
    NavSeries reference;
    if (!in.truth.empty()) reference = NavSeries::from_records(read_nav(in.truth));
    const NavSeries* ref = in.truth.empty() ? nullptr : &reference;
    page.paragraph("Solution " + in.nav + ": " + std::to_string(nav.size()) + " epochs over " +
                   fixed(nav.t_end_s() - nav.t_begin_s(), 1) + " s" +
                   (ref ? "; compared with " + in.reference_label + " " + in.truth : "") + ".");
    add_trajectory_section(page, dir, nav, ref, in);
    add_error_section(page, dir, nav, ref, in);
    if (!in.forward.empty() || !in.separation.empty()) add_smoothing_section(page, dir, nav, ref, in);
  }
  if (!in.innovations.empty()) add_innovation_section(page, dir, in);
  if (!in.outage_json.empty())
    json_section(in.outage_json, "`ldv outage --json`", [&] { add_outage_section(page, dir, in); });
  if (!in.allan_json.empty())
    json_section(in.allan_json, "`ldv allan --json`", [&] { add_allan_section(page, dir, in); });
  if (!in.allan_loop_json.empty())
    json_section(in.allan_loop_json.size() == 1 ? in.allan_loop_json.front() : "the stochastic loop's files",
                 "`ldv allan --json`", [&] { add_stochastic_loop_section(page, dir, in); });
  if (!in.diagnose_json.empty())
    json_section(in.diagnose_json, "`ldv diagnose --json`", [&] { add_diagnosis_section(page, dir, in); });
  const std::string index = (fs::path(dir) / "index.html").string();
  page.write(index);
  return index;
}

}  // namespace ldv::assess
