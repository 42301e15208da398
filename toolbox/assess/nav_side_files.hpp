#pragma once
// The files `ldv nav` writes beside FILE.nav (estimator/README.md):
//   FILE_std.txt          week sow, 1-sigma of position NED [m], velocity NED [m/s], roll pitch yaw [deg], ...
//   FILE_innovations.txt  t_sow kind innov_1..3 sqrtS_11..33 nis accepted
// and `ldv smooth` (tools/ldv/nav_outputs.hpp):
//   FILE_separation.txt   week sow, forward minus smoothed (9: NED m, NED m/s, phi NED deg), its expected 1-sigma (9)
//   FILE_forward.nav      the forward solution (and its _std.txt, _innovations.txt)
#include <string>
#include <vector>

#include "common/math/rotation.hpp"

namespace ldv::assess {

struct StdRow {
  double t_s = 0.0;
  Vec3 pos_ned_m = Vec3::Zero(), vel_ned_mps = Vec3::Zero(), att_deg = Vec3::Zero();
};

struct InnovationRow {
  double t_s = 0.0;
  std::string kind;  // gnss_position, gnss_velocity, zupt
  Vec3 innovation = Vec3::Zero();  // predicted minus measured, NED
  Vec3 sqrt_S = Vec3::Zero();      // its predicted 1-sigma
  double nis = 0.0;
  bool accepted = true;
};

// "run.nav" -> "run_std.txt" / "run_innovations.txt" / "run_separation.txt" / "run_forward.nav"
std::string std_path_for(const std::string& nav_path);
std::string innovations_path_for(const std::string& nav_path);
std::string separation_path_for(const std::string& nav_path);
std::string forward_path_for(const std::string& nav_path);

struct SeparationRow {
  double t_s = 0.0;
  Eigen::Matrix<double, 9, 1> separation = Eigen::Matrix<double, 9, 1>::Zero();  // m, m/s, deg
  Eigen::Matrix<double, 9, 1> std = Eigen::Matrix<double, 9, 1>::Zero();         // its expected 1-sigma
};

// Throw InputError (file, line) on malformed rows.
std::vector<StdRow> read_std_file(const std::string& path);
std::vector<InnovationRow> read_innovations_file(const std::string& path);
std::vector<SeparationRow> read_separation_file(const std::string& path);

}  // namespace ldv::assess
