#pragma once
// `ldv calib static` as a library: detect static poses, adjust the accelerometer on the magnitude of
// gravity, then the gyro on the magnitude (and angle to gravity) of Earth rate where it can sense it, or by
// integrating the rotations between poses where it cannot; each adjustment with rank and observability
// checks and the EV damping sweep.
#include <optional>
#include <string>
#include <vector>

#include "toolbox/calib/damping_sweep.hpp"
#include "toolbox/calib/gauss_helmert.hpp"
#include "common/formats/imu_calibration.hpp"
#include "toolbox/calib/imu_log.hpp"
#include "toolbox/calib/static_poses.hpp"

namespace ldv::calib {

enum class GyroMethod { kAuto, kEarthRate, kRotation, kNone };
GyroMethod parse_gyro_method(const std::string& name);  // auto | earth-rate | rotation | none
const char* to_string(GyroMethod m);

struct StaticCalibrationOptions {
  StaticDetectorOptions detector;       // threshold_multiplier 0: sweep 2..10 (imu_tk)
  double lat_rad = 45.0 * kDegToRad;
  double h_m = 0.0;
  std::optional<double> gravity_mps2;   // overrides the normal gravity at (lat, h)
  GyroMethod gyro_method = GyroMethod::kAuto;
  double gyro_full_scale_rad_s = 0.0;   // clipping level; 0: detected from the log
  std::optional<double> ev;             // damping; empty: chosen by the sweep
  std::vector<double> ev_grid = default_ev_grid();
};

// One adjustment (accelerometer, or gyro by one method) and what it says about itself.
struct Adjustment {
  std::string name;             // "accel (gravity magnitude)", ...
  bool attempted = false;
  bool solved = false;          // false: refused (the reason says why); no parameters were produced
  std::string refusal;
  std::vector<std::string> param_names;
  std::vector<std::string> param_units;  // display units per parameter
  std::vector<double> param_display_scale;  // SI -> display
  GaussHelmertResult result;    // at the chosen EV
  ObservabilityReport undamped_observability;
  DampingSweep sweep;
  double ev = 0.0;
  std::string residual_unit;    // of the per-block misclosure
  std::vector<std::string> block_labels;  // "pose 3" or "pose 3 -> 4"
};

struct ThresholdTrial {
  double multiplier = 0.0;
  size_t poses = 0;
  double residual_std_mps2 = NAN;  // sqrt(sum w^2 / (n - 9)) of the gravity magnitude, NaN if not solvable
};

struct StaticCalibrationResult {
  double gravity_mps2 = 0.0;
  StaticDetection detection;
  std::vector<ThresholdTrial> threshold_trials;
  Adjustment accel;
  Adjustment gyro_earth_rate;
  Adjustment gyro_rotation;
  GyroMethod gyro_method_used = GyroMethod::kNone;
  std::vector<double> gravity_residual_before_mps2;  // |f_mean| - g per pose, nominal conversion only
  std::vector<double> gravity_residual_after_mps2;   // after calibration
  std::vector<double> rotation_residual_rad;         // gyro rotation method: angle per transition used
  std::vector<size_t> clipped_transitions;           // pose k -> k+1 left out: the gyro clipped
  ImuCalibration calibration;
  bool ok() const { return accel.solved; }
};

StaticCalibrationResult calibrate_static(const ImuLog& log, const StaticCalibrationOptions& opt);

}  // namespace ldv::calib
