#pragma once
// The file-input options of `ldv nav`, `ldv outage` and `ldv diagnose` (loaded by
// toolbox/assess/nav_inputs.hpp).
#include <CLI/CLI.hpp>

#include "estimator/update/updater.hpp"
#include "toolbox/assess/nav_inputs.hpp"
#include "tools/ldv/cli_checks.hpp"

namespace ldv::cli {

inline void add_nav_input_options(CLI::App* c, assess::NavInputArgs& in, bool config_required = false) {
  auto* config = c->add_option("--kfgins-config", in.config,
                               "KF-GINS YAML configuration (paths, rates, init state, imunoise, antlever, ldv: keys)");
  if (config_required) config->required();
  c->add_option("--imu", in.imu, "IMU increments (KF-GINS imu.txt), overrides the config");
  c->add_option("--imu-csv", in.imu_csv, "IMU rates as CSV ax,ay,az[g],gx,gy,gz[deg/s],counter[ms] with an RTKLIB tag file");
  c->add_option("--imu-tag", in.imu_tag, "RTKLIB time-tag file of --imu-csv (default FILE.tag)");
  c->add_option("--csv-axes", in.csv_axes, "device axes to front-right-down, e.g. 1 -2 -3 (default 1 2 3)")
      ->expected(3)
      ->check(ldv::cli::finite_range(-3, 3));
  c->add_option("--imu-time-shift", in.imu_time_shift_s,
                "added to every IMU time stamp [s]: a known IMU latency (default ldv.imu_time_shift_s; the time_offset "
                "effect estimates an unknown one)")
      ->check(ldv::cli::finite_range(-604800, 604800));
  c->add_option("--calibration", in.calibration,
                "IMU calibration file of `ldv calib static`, applied to every increment in the device axes "
                "(default ldv.calibration; toolbox/calib/README.md)");
  c->add_option("--gnss", in.gnss, "GNSS solutions (7- or 13-column KF-GINS gnss.txt), overrides the config");
  c->add_option("--pos", in.rtklib_pos, "GNSS solutions from an RTKLIB .pos file, overrides the config");
  c->add_option("--pos-height-offset", in.pos_height_offset_m,
                "added to the .pos heights [m]: the geoid separation N when the file gives height above MSL "
                "(default ldv.pos_height_offset_m; 21.387 for walk_0827)")
      ->check(ldv::cli::finite_range(-1e4, 1e4));
  c->add_option("--float-std-min", in.float_std_min_m,
                "minimum position std [m] of .pos solutions that are not RTK-fixed (default ldv.float_std_min_m, "
                "0: as reported)")
      ->check(ldv::cli::finite_range(0, 1e4));
  c->add_option("--model", in.model, "ins15 | kfgins21 | geoldv51 (default ldv.model, else kfgins21)");
  c->add_option("--add", in.add, "add an effect block (repeatable)");
  c->add_option("--drop", in.drop, "drop an effect block (repeatable)");
  c->add_option("--lever", in.lever, "antenna lever arm x y z [m], body front-right-down")
      ->expected(3)
      ->check(ldv::cli::finite_range(-100, 100));
  c->add_option("--imu-latency", in.imu_latency,
                "auto: estimate how late the IMU stamps are from the turns and take it out when significant; off "
                "(default ldv.imu_latency, else auto; off with --imu-time-shift or --kfgins-compatible)")
      ->check(CLI::IsMember({"auto", "off"}));
  c->add_flag("--kfgins-compatible", in.kfgins_compatible,
              "do what KF-GINS does: every GNSS fix updates the filter (no gate, no robust update), no noise "
              "adaptation, no latency search (default ldv.kfgins_compatible, else off)");
  c->add_option("--aid", in.aids,
                "land-vehicle aid (repeatable): nhc (non-holonomic constraint), zaru (zero angular rate at stops), "
                "odometer (wheel speed from --odometer or ldv.odopath); default ldv.aids, else none")
      ->check(CLI::IsMember(est::aid_names()));
  c->add_option("--odometer", in.odometer,
                "odometer speeds: text file, one line per reading 'sow speed_mps' (default ldv.odopath)");
  c->add_flag("--strict", in.strict,
              "refuse inputs that drop more than 2 % of a file's records or hold an IMU gap over 1 s (default: a "
              "warning)");
}

}  // namespace ldv::cli
