#pragma once
// The file-input options shared by `ldv outage` and `ldv diagnose` (those of `ldv nav`; loaded by
// toolbox/assess/nav_inputs.hpp).
#include <CLI/CLI.hpp>

#include "toolbox/assess/nav_inputs.hpp"

namespace ldv::cli {

inline void add_nav_input_options(CLI::App* c, assess::NavInputArgs& in, bool config_required = false) {
  auto* config = c->add_option("--kfgins-config", in.config, "KF-GINS YAML configuration (as ldv nav)");
  if (config_required) config->required();
  c->add_option("--imu", in.imu, "IMU increments (KF-GINS imu.txt), overrides the config");
  c->add_option("--gnss", in.gnss, "GNSS solutions (KF-GINS gnss.txt), overrides the config");
  c->add_option("--imu-csv", in.imu_csv, "tagged IMU CSV (ax,ay,az [g], gx,gy,gz [deg/s], counter [ms])");
  c->add_option("--imu-tag", in.imu_tag, "RTKLIB time-tag file of --imu-csv (default FILE.tag)");
  c->add_option("--csv-axes", in.csv_axes, "device axes to front-right-down, e.g. 1 -2 -3 (default 1 2 3)")->expected(3);
  c->add_option("--pos", in.rtklib_pos, "GNSS solutions as an RTKLIB .pos file");
  c->add_option("--pos-height-offset", in.pos_height_offset_m, "added to the .pos heights [m] (default ldv.pos_height_offset_m)");
  c->add_option("--float-std-min", in.float_std_min_m, "position std floor of non-fixed .pos solutions [m] (default ldv.float_std_min_m)");
  c->add_option("--imu-time-shift", in.imu_time_shift_s, "added to every IMU time stamp [s] (default ldv.imu_time_shift_s)");
  c->add_option("--calibration", in.calibration,
                "IMU calibration file of `ldv calib static`, applied to every increment in the device axes (default ldv.calibration)");
  c->add_option("--model", in.model, "ins15 | kfgins21 | geoldv51");
  c->add_option("--add", in.add, "add an effect block (repeatable)");
  c->add_option("--drop", in.drop, "drop an effect block (repeatable)");
  c->add_option("--lever", in.lever, "antenna lever arm x y z [m], body front-right-down")->expected(3);
}

}  // namespace ldv::cli
