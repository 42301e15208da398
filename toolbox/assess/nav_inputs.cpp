#include "toolbox/assess/nav_inputs.hpp"

#include <cstdlib>

#include "common/formats/kfgins_files.hpp"
#include "common/formats/tagged_imu_csv.hpp"
#include "common/io/input_error.hpp"
#include "estimator/run/run_navigation.hpp"
#include "services/gnss_link/protocols/rtklib_solution.hpp"

namespace ldv::assess {
namespace {

Vec3 remap(const Vec3& v, const std::vector<int>& axes) {
  Vec3 out;
  for (int i = 0; i < 3; ++i) out(i) = (axes[i] > 0 ? 1.0 : -1.0) * v(std::abs(axes[i]) - 1);
  return out;
}

void check_axes(const std::vector<int>& axes) {
  int seen = 0;
  for (int a : axes)
    if (std::abs(a) >= 1 && std::abs(a) <= 3) seen |= 1 << std::abs(a);
  if (axes.size() != 3 || seen != 0b1110) throw InputError("--csv-axes", 0, "expected a permutation of 1 2 3 with signs, e.g. 1 -2 -3");
}

}  // namespace

NavInputs load_nav_inputs(const NavInputArgs& a) {
  NavInputs in;
  if (!a.config.empty()) {
    in.config = load_kfgins_config(a.config);
    in.options = est::options_from_kfgins(in.config);
  }
  if (!a.imu.empty()) in.config.imu_path = a.imu;
  if (!a.gnss.empty()) in.config.gnss_path = a.gnss;
  if (a.lever.size() == 3) in.options.lever_arm.init = Vec3(a.lever[0], a.lever[1], a.lever[2]);
  if (!a.model.empty()) in.options.model = a.model;
  in.options.add.insert(in.options.add.end(), a.add.begin(), a.add.end());
  in.options.drop.insert(in.options.drop.end(), a.drop.begin(), a.drop.end());

  if (!a.imu_csv.empty()) {
    check_axes(a.csv_axes);
    if (a.imu_tag.empty()) throw InputError(a.imu_csv, 0, "a tagged IMU CSV needs its time-tag file (--imu-tag)");
    in.imu = read_tagged_imu_csv(a.imu_csv, a.imu_tag);
    for (ImuIncrement& s : in.imu) {
      s.dtheta_b_rad = remap(s.dtheta_b_rad, a.csv_axes);
      s.dvel_b_mps = remap(s.dvel_b_mps, a.csv_axes);
    }
    in.description = a.imu_csv;
  } else {
    if (in.config.imu_path.empty()) throw InputError("ldv", 0, "give --kfgins-config FILE, or --imu FILE (or --imu-csv FILE --imu-tag FILE)");
    in.imu = read_kfgins_imu(in.config.imu_path);
    in.description = in.config.imu_path;
  }
  if (!a.rtklib_pos.empty()) {
    for (const gnss::GnssSolution& s : gnss::read_rtklib_pos(a.rtklib_pos)) in.gnss.push_back(s.fix);
    in.description += " + " + a.rtklib_pos;
  } else {
    if (in.config.gnss_path.empty()) throw InputError("ldv", 0, "give --kfgins-config FILE, or --gnss FILE (or --pos FILE)");
    in.gnss = read_kfgins_gnss(in.config.gnss_path);
    in.description += " + " + in.config.gnss_path;
  }
  return in;
}

}  // namespace ldv::assess
