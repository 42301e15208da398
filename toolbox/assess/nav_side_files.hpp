#pragma once
// The files `ldv nav` writes beside FILE.nav (estimator/README.md):
//   FILE_std.txt          week sow, 1-sigma of position NED [m], velocity NED [m/s], roll pitch yaw [deg], ...
//   FILE_innovations.txt  t_sow kind innov_1..3 sqrtS_11..33 nis accepted
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

// "run.nav" -> "run_std.txt" / "run_innovations.txt"
std::string std_path_for(const std::string& nav_path);
std::string innovations_path_for(const std::string& nav_path);

// Throw InputError (file, line) on malformed rows.
std::vector<StdRow> read_std_file(const std::string& path);
std::vector<InnovationRow> read_innovations_file(const std::string& path);

}  // namespace ldv::assess
