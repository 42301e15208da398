#pragma once
// The inputs `ldv nav` takes (a KF-GINS configuration, file overrides, model changes), loaded once for
// the assessment commands; also the real walk's layout (IMU CSV + RTKLIB tags, RTKLIB .pos).
#include <string>
#include <vector>

#include "common/formats/kfgins_config.hpp"
#include "common/formats/nav_types.hpp"
#include "estimator/options.hpp"

namespace ldv::assess {

struct NavInputArgs {
  std::string config;              // KF-GINS YAML
  std::string imu, gnss;           // KF-GINS imu.txt / gnss.txt (override the config)
  std::string imu_csv, imu_tag;    // tagged IMU CSV (common/formats/tagged_imu_csv.hpp)
  std::string rtklib_pos;          // RTKLIB .pos GNSS solutions
  std::string model;
  std::vector<std::string> add, drop;
  std::vector<double> lever;       // x y z [m] FRD
  // The tagged CSV's axes into front-right-down: each entry is +-1..3 (device axis, sign), e.g. the
  // walk's x-forward, y-left, z-up device: {1, -2, -3}.
  std::vector<int> csv_axes = {1, 2, 3};
};

struct NavInputs {
  KfGinsConfig config;
  est::FilterOptions options;
  std::vector<ImuIncrement> imu;
  std::vector<GnssFix> gnss;
  std::string description;  // one line for the log
};

// Throws InputError naming what is missing or wrong.
NavInputs load_nav_inputs(const NavInputArgs& args);

}  // namespace ldv::assess
