#pragma once
// The file inputs of `ldv nav`, `ldv outage` and `ldv diagnose` (a KF-GINS configuration, file overrides,
// model changes), loaded in one place. Besides KF-GINS text files, the IMU may be a time-tagged CSV (the real
// walk's layout: a path ending in .csv, its RTKLIB tag file beside it as FILE.tag) and the GNSS an RTKLIB
// .pos file (a path ending in .pos), given on the command line or as imupath / gnsspath in the configuration.
// Adjustments, from the command line or else the configuration's `ldv:` section:
//   pos_height_offset_m  added to .pos heights (the geoid separation when the file gives height above MSL)
//   float_std_min_m      floor of the position std of .pos solutions that are not RTK-fixed
//   imu_time_shift_s     added to every IMU time stamp (a known IMU latency)
//   calibration          an `ldv calib static` calibration file (toolbox/calib/README.md) applied to every IMU
//                        increment; a relative path resolves like imupath (working directory, else beside the
//                        configuration). Command line: --calibration FILE (relative to the working directory).
// The calibration is applied in the axes the file was recorded in (the device's, which are the ones
// `ldv calib static` saw in its log), before --csv-axes turns a tagged CSV into front-right-down:
//   true = M^-1 (meas - bias * dt), M = (I + diag(scale) + N(misalignment)) C_b_s   (docs/effects.md)
// When the calibration carries sigmas (all three axes > 0) they become the prior std of the filter's gyro_bias,
// accel_bias, gyro_scale and accel_scale blocks, unless the configuration gives that prior (initbgstd,
// initbastd, initsgstd, initsastd): after the calibration, what is left of those errors is its uncertainty.
// NavInputs::imu_note says what was applied.
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "common/formats/kfgins_config.hpp"
#include "common/formats/nav_types.hpp"
#include "common/io/dropped_records.hpp"
#include "estimator/calibrate/drive_imu_latency.hpp"
#include "estimator/calibrate/gnss_velocity_check.hpp"
#include "estimator/calibrate/imu_stamp_jitter.hpp"
#include "estimator/options.hpp"
#include "estimator/update/observation.hpp"
#include "input/drive_sources.hpp"

namespace ldv::assess {

struct NavInputArgs {
  std::string config;              // KF-GINS YAML
  std::string imu, gnss;           // KF-GINS imu.txt / gnss.txt (override the config)
  std::string imu_csv, imu_tag;    // tagged IMU CSV (common/formats/tagged_imu_csv.hpp)
  std::string rtklib_pos;          // RTKLIB .pos GNSS solutions
  std::string model;
  std::vector<std::string> add, drop;
  std::vector<double> lever;       // x y z [m] FRD
  bool kfgins_compatible = false;  // KF-GINS's gate instead of the robust update (FilterOptions::robust_update)
  // IMU time-tag latency: "auto" estimates it from the gyros and the GNSS track and takes it out when it
  // is significant (estimator/calibrate/imu_latency.hpp); "off". Empty: ldv.imu_latency, else auto (off
  // with --kfgins-compatible or a given imu_time_shift_s).
  std::string imu_latency;
  // A latency taken out is refined by a filter pass with the time_offset state (its residual, the estimate's
  // sigma as the prior), unless the model has time_offset already. Off in `ldv diagnose` (whose check judges
  // the model it is given, and which names time_offset itself when the data ask for it).
  bool refine_latency_in_filter = true;
  // The tagged CSV's axes into front-right-down: each entry is +-1..3 (device axis, sign), e.g. the
  // walk's x-forward, y-left, z-up device: {1, -2, -3}.
  std::vector<int> csv_axes = {1, 2, 3};
  std::string calibration;         // IMU calibration file (overrides the configuration's ldv.calibration)
  // kUnset: take the configuration's ldv: value (default 0).
  double pos_height_offset_m = kUnset, float_std_min_m = kUnset, imu_time_shift_s = kUnset;
  static constexpr double kUnset = -1e300;
  // --strict: an input file that loses more than kMaxDroppedFraction of its records (or an IMU with a gap
  // longer than kMaxImuGap_s) is an error (InputError) instead of a warning.
  bool strict = false;
  // Land-vehicle aids (estimator/options.hpp AidOptions): replace ldv.aids when given; the odometer file
  // replaces ldv.odopath.
  std::vector<std::string> aids;
  std::string odometer;
};

// What the readers kept and dropped of one input file (printed by `ldv nav`).
using InputFileCounts = input::SourceCounts;

constexpr double kMaxDroppedFraction = 0.02;  // more is worth a warning (and an error with --strict)
constexpr double kMaxImuGap_s = 1.0;          // an IMU hole longer than this is worth a warning

struct NavInputs {
  KfGinsConfig config;
  est::FilterOptions options;
  std::vector<ImuIncrement> imu;
  std::vector<GnssFix> gnss;
  std::string description;  // one line for the log
  std::string imu_note;     // what the IMU reader skipped or assumed
  std::string gnss_note;    // what the .pos reader skipped or reordered
  // From a .pos file (its earliest week), else -1. .pos fix times are seconds since the start of this week,
  // continuous across a week rollover (past 604800 s).
  int gps_week = -1;
  // What the IMU latency search found and decided (NavInputArgs::imu_latency; estimator/calibrate/
  // drive_imu_latency.hpp): `latency.turns` when estimated, `latency.applied` when a lag was taken out.
  est::DriveImuLatency latency;
  // What was decided about the GNSS velocities (estimator/calibrate/gnss_velocity_check.hpp), "" if none.
  std::string gnss_velocity_note;
  std::optional<est::GnssVelocityCheck> gnss_velocity_check;
  // The IMU tags' jitter measured from a tagged CSV's rows (run_navigation measures it from other files' increments).
  est::ImuStampJitter imu_stamp_jitter;      // what that decision rested on, when it was made
  std::vector<InputFileCounts> file_counts;  // IMU then GNSS
  std::vector<ImuTimeGap> imu_gaps;          // IMU intervals > 10 median intervals (kept: the estimator decides)
  // Readings of the other sensors (odometer with --aid odometer), in time order: run_navigation's `others`.
  std::vector<est::ObservationPtr> other_observations;
};

// One line per input file ("IMU imu.txt: 1000 kept, 3 dropped: 3 wrong column count (first: ...)").
std::vector<std::string> input_count_lines(const NavInputs& in);
// Warnings: a file that dropped more than kMaxDroppedFraction of its records, IMU gaps longer than kMaxImuGap_s.
std::vector<std::string> input_warnings(const NavInputs& in);

// The configuration and the filter options with the command line's model changes, no data read (the
// config's output path defaults to "." without a config). Throws InputError naming what is wrong.
NavInputs load_nav_model(const NavInputArgs& args);
// That, plus the IMU and GNSS data. Throws InputError naming what is missing or wrong.
NavInputs load_nav_inputs(const NavInputArgs& args);

}  // namespace ldv::assess
