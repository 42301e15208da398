#include "toolbox/assess/nav_side_files.hpp"

#include "common/io/input_error.hpp"
#include "common/io/text_table.hpp"

namespace ldv::assess {
namespace {
std::string base_of(const std::string& nav_path) {
  const bool nav = nav_path.size() > 4 && nav_path.compare(nav_path.size() - 4, 4, ".nav") == 0;
  return nav ? nav_path.substr(0, nav_path.size() - 4) : nav_path;
}
}  // namespace

std::string std_path_for(const std::string& nav_path) { return base_of(nav_path) + "_std.txt"; }
std::string innovations_path_for(const std::string& nav_path) { return base_of(nav_path) + "_innovations.txt"; }
std::string separation_path_for(const std::string& nav_path) { return base_of(nav_path) + "_separation.txt"; }
std::string forward_path_for(const std::string& nav_path) { return base_of(nav_path) + "_forward.nav"; }

std::vector<SeparationRow> read_separation_file(const std::string& path) {
  std::vector<SeparationRow> rows;
  read_numeric_table(path, 20, 20, [&](long, const std::vector<double>& v) {
    SeparationRow r;
    r.t_s = v[1];
    for (int k = 0; k < 9; ++k) {
      r.separation(k) = v[2 + k];
      r.std(k) = v[11 + k];
    }
    rows.push_back(r);
  });
  return rows;
}

std::vector<StdRow> read_std_file(const std::string& path) {
  std::vector<StdRow> rows;
  // week sow + 9 navigation stds, then two columns per effect state (any number).
  read_numeric_table(path, 11, 100000, [&](long line, const std::vector<double>& v) {
    // Standard deviations are >= 0: a .nav given in its place (latitudes, negative velocities) is refused
    for (int i = 2; i <= 10; ++i)
      if (!(v[i] >= 0.0))
        throw InputError(path, line,
                         "column " + std::to_string(i + 1) + ": expected a standard deviation (>= 0), found " +
                             std::to_string(v[i]) + ": is this the _std.txt of an `ldv nav` run?");
    StdRow r;
    r.t_s = v[1];
    r.pos_ned_m = Vec3(v[2], v[3], v[4]);
    r.vel_ned_mps = Vec3(v[5], v[6], v[7]);
    r.att_deg = Vec3(v[8], v[9], v[10]);
    rows.push_back(r);
  });
  return rows;
}

std::vector<InnovationRow> read_innovations_file(const std::string& path) {
  TextFileLines f(path);  // bounded line length; refuses devices and directories
  std::vector<InnovationRow> rows;
  std::vector<std::string_view> fields;
  std::string_view line;
  while (f.next(line)) {
    const long n = f.line_number();
    if (line.empty() || line[0] == '#') continue;
    split_fields(line, fields);
    if (fields.size() != 10) throw InputError(path, n, "expected 10 columns: t kind innov x3 sqrtS x3 nis accepted");
    InnovationRow r;
    r.t_s = parse_double(fields[0], path, n, 1);
    r.kind = std::string(fields[1]);
    for (int i = 0; i < 3; ++i) {
      r.innovation(i) = parse_double(fields[2 + i], path, n, 3 + i);
      r.sqrt_S(i) = parse_double(fields[5 + i], path, n, 6 + i);
    }
    r.nis = parse_double(fields[8], path, n, 9);
    r.accepted = parse_double(fields[9], path, n, 10) != 0.0;
    rows.push_back(r);
  }
  return rows;
}

}  // namespace ldv::assess
