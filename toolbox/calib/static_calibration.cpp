#include "toolbox/calib/static_calibration.hpp"

#include <cmath>

#include "common/geo/earth_model.hpp"
#include "common/io/input_error.hpp"
#include "toolbox/calib/accel_gravity_model.hpp"
#include "toolbox/calib/gyro_earth_rate_model.hpp"
#include "toolbox/calib/gyro_rotation_model.hpp"

namespace ldv::calib {

GyroMethod parse_gyro_method(const std::string& name) {
  if (name == "auto") return GyroMethod::kAuto;
  if (name == "earth-rate") return GyroMethod::kEarthRate;
  if (name == "rotation") return GyroMethod::kRotation;
  if (name == "none") return GyroMethod::kNone;
  throw InputError("--gyro-method", 0, "unknown method '" + name + "' (auto, earth-rate, rotation, none)");
}

const char* to_string(GyroMethod m) {
  switch (m) {
    case GyroMethod::kAuto: return "auto";
    case GyroMethod::kEarthRate: return "earth-rate";
    case GyroMethod::kRotation: return "rotation";
    case GyroMethod::kNone: return "none";
  }
  return "?";
}

namespace {

constexpr double kRadPerSToDegPerH = kRadToDeg * 3600.0;

void set_units(Adjustment& a, const std::vector<std::string>& names) {
  a.param_names = names;
  for (const std::string& n : names) {
    std::string unit = "-";
    double scale = 1.0;
    if (n.find("accel_bias") == 0) unit = "m/s^2";
    else if (n.find("gyro_bias") == 0) unit = "deg/h", scale = kRadPerSToDegPerH;
    else if (n.find("scale") != std::string::npos) unit = "ppm", scale = 1e6;
    else unit = "mrad", scale = 1e3;  // misalignment, rotation
    a.param_units.push_back(unit);
    a.param_display_scale.push_back(scale);
  }
}

std::string join(const std::vector<std::string>& v, const char* sep) {
  std::string s;
  for (const std::string& e : v) s += (s.empty() ? "" : sep) + e;
  return s;
}

// Sets the refusal when the normal matrix is rank deficient (or, if asked, a direction is unresolved).
bool refuse(Adjustment& adj, size_t n_blocks, int n_params, bool refuse_unresolved) {
  const ObservabilityReport& ob = adj.undamped_observability;
  const int conditions = adj.result.redundancy + n_params;
  if (ob.rank_deficient) {
    adj.refusal = "rank deficient: " + std::to_string(n_blocks) + " poses/transitions give " +
                  std::to_string(conditions) + " conditions for " + std::to_string(n_params) +
                  " unknowns (see the weak directions for what the data cannot determine)";
    return true;
  }
  if (refuse_unresolved && ob.unresolved) {
    adj.refusal = "not observable against the noise: " + std::to_string(ob.weak_directions.size()) +
                  " parameter directions have a sigma larger than the physical range (" +
                  join(ob.unresolved_parameters, "; ") + ")";
    return true;
  }
  return false;
}

// Undamped solve -> rank and resolution check -> EV sweep -> solve at the chosen EV.
void run_adjustment(Adjustment& adj, const ConditionModel& model, const std::vector<ConditionBlock>& blocks,
                    const VectorXd& x0, const StaticCalibrationOptions& opt, bool refuse_unresolved) {
  adj.attempted = true;
  set_units(adj, model.param_names());
  // Judge the design at the start values first: a problem the data cannot determine is refused before
  // any iteration can wander off (MEMS Earth rate, too few poses).
  GaussHelmertOptions probe;
  probe.max_iterations = 0;
  adj.result = solve_gauss_helmert(model, blocks, x0, probe);
  adj.undamped_observability = adj.result.observability;
  if (refuse(adj, blocks.size(), model.num_params(), refuse_unresolved)) return;
  GaussHelmertOptions gh;
  const GaussHelmertResult undamped = solve_gauss_helmert(model, blocks, x0, gh);
  adj.undamped_observability = undamped.observability;
  adj.result = undamped;
  if (refuse(adj, blocks.size(), model.num_params(), refuse_unresolved)) return;
  if (!undamped.converged) {
    adj.refusal = "the adjustment did not converge in " + std::to_string(gh.max_iterations) + " iterations";
    return;
  }
  if (!opt.ev_grid.empty()) adj.sweep = sweep_damping(model, blocks, undamped.x, opt.ev_grid);
  adj.ev = opt.ev ? *opt.ev : (adj.sweep.points.empty() ? 0.0 : adj.sweep.best().ev);
  if (adj.ev > 0.0) {
    gh.ev = adj.ev;
    adj.result = solve_gauss_helmert(model, blocks, undamped.x, gh);
  }
  adj.solved = true;
}

double gravity_residual_std(const ImuLog&, const std::vector<Pose>& poses, double g) {
  if (poses.size() < 10) return NAN;
  AccelGravityModel model(g);
  const GaussHelmertResult r =
      solve_gauss_helmert(model, AccelGravityModel::blocks(poses), AccelGravityModel::initial_guess(poses, g));
  if (r.observability.rank_deficient || !r.converged) return NAN;
  double ss = 0.0;
  for (const VectorXd& w : r.misclosure) ss += w.squaredNorm();
  return std::sqrt(ss / (static_cast<double>(poses.size()) - 9.0));
}

StaticDetection detect(const ImuLog& log, const StaticCalibrationOptions& opt, double g,
                       std::vector<ThresholdTrial>& trials) {
  if (opt.detector.threshold_multiplier > 0.0) return detect_static_poses(log, opt.detector);
  // imu_tk's search over the threshold multiplier, judged by the unbiased residual std of the gravity fit
  // (a pose polluted by motion shows up there; a pose's own scatter does not hide it).
  StaticDetection best;
  double best_std = INFINITY;
  for (int k = 2; k <= 10; ++k) {
    StaticDetectorOptions o = opt.detector;
    o.threshold_multiplier = k;
    StaticDetection d = detect_static_poses(log, o);
    ThresholdTrial t{static_cast<double>(k), d.poses.size(), gravity_residual_std(log, d.poses, g)};
    trials.push_back(t);
    const bool better = std::isfinite(t.residual_std_mps2)
                            ? t.residual_std_mps2 < best_std
                            : (!std::isfinite(best_std) && d.poses.size() > best.poses.size());
    if (better || best.poses.empty()) {
      if (std::isfinite(t.residual_std_mps2)) best_std = t.residual_std_mps2;
      best = std::move(d);
    }
  }
  return best;
}

std::vector<std::string> pose_labels(size_t n, bool transitions) {
  std::vector<std::string> l;
  for (size_t k = 0; k < n; ++k)
    l.push_back(transitions ? std::to_string(k + 1) + "->" + std::to_string(k + 2) : std::to_string(k + 1));
  return l;
}

}  // namespace

StaticCalibrationResult calibrate_static(const ImuLog& log, const StaticCalibrationOptions& opt) {
  StaticCalibrationResult res;
  res.gravity_mps2 = opt.gravity_mps2 ? *opt.gravity_mps2 : earth::gravity_n(opt.lat_rad, opt.h_m).norm();
  StaticCalibrationOptions o = opt;
  if (o.detector.init_static_s <= 0.0) o.detector.init_static_s = log.init_static_s.value_or(30.0);
  res.detection = detect(log, o, res.gravity_mps2, res.threshold_trials);
  const std::vector<Pose>& poses = res.detection.poses;
  res.calibration.description = "ldv calib static: " + log.source + ", " + std::to_string(poses.size()) + " poses";

  // Accelerometer.
  res.accel.name = "accelerometer: gravity magnitude (Gauss-Helmert)";
  res.accel.residual_unit = "m/s^2";
  res.accel.block_labels = pose_labels(poses.size(), false);
  const AccelGravityModel accel_model(res.gravity_mps2);
  run_adjustment(res.accel, accel_model, AccelGravityModel::blocks(poses),
                 AccelGravityModel::initial_guess(poses, res.gravity_mps2), o, false);
  for (const Pose& p : poses) res.gravity_residual_before_mps2.push_back(p.f_mean_mps2.norm() - res.gravity_mps2);
  if (!res.accel.solved) return res;
  res.calibration.accel = AccelGravityModel::to_triad(res.accel.result.x, res.accel.result.sigma());
  for (const Pose& p : poses)
    res.gravity_residual_after_mps2.push_back(res.calibration.accel.correct(p.f_mean_mps2).norm() - res.gravity_mps2);

  // Gyro.
  if (!log.has_gyro() || o.gyro_method == GyroMethod::kNone) return res;
  if (o.gyro_method == GyroMethod::kAuto || o.gyro_method == GyroMethod::kEarthRate) {
    res.gyro_earth_rate.name = "gyro: Earth-rate magnitude and angle to gravity (Gauss-Helmert)";
    res.gyro_earth_rate.residual_unit = "deg/h";
    res.gyro_earth_rate.block_labels = pose_labels(poses.size(), false);
    const GyroEarthRateModel model(res.calibration.accel, o.lat_rad, o.h_m);
    run_adjustment(res.gyro_earth_rate, model, GyroEarthRateModel::blocks(poses),
                   GyroEarthRateModel::initial_guess(poses), o, true);
    if (res.gyro_earth_rate.solved) {
      res.gyro_method_used = GyroMethod::kEarthRate;
      res.calibration.gyro = GyroEarthRateModel::to_triad(res.gyro_earth_rate.result.x, res.gyro_earth_rate.result.sigma());
      return res;
    }
    if (o.gyro_method == GyroMethod::kEarthRate) return res;
  }
  res.gyro_rotation.name = "gyro: rotation between static poses (Gauss-Helmert, imu_tk style)";
  res.gyro_rotation.residual_unit = "rad";
  res.gyro_rotation.block_labels = pose_labels(poses.size() > 0 ? poses.size() - 1 : 0, true);
  if (poses.size() < 2) {
    res.gyro_rotation.attempted = true;
    res.gyro_rotation.refusal = "needs at least two static poses";
    return res;
  }
  const GyroRotationModel model(log, poses, res.calibration.accel, find_clipped_samples(log, o.gyro_full_scale_rad_s));
  res.clipped_transitions = model.clipped_transitions();
  res.gyro_rotation.block_labels.clear();
  for (size_t k : model.transitions())
    res.gyro_rotation.block_labels.push_back(std::to_string(k + 1) + "->" + std::to_string(k + 2));
  run_adjustment(res.gyro_rotation, model, model.blocks(), VectorXd::Zero(9), o, false);
  if (!res.gyro_rotation.solved) return res;
  res.gyro_method_used = GyroMethod::kRotation;
  res.calibration.gyro = model.to_triad(res.gyro_rotation.result.x, res.gyro_rotation.result.sigma());
  for (size_t k = 0; k < model.transitions().size(); ++k)
    res.rotation_residual_rad.push_back(model.angle_residual_rad(static_cast<int>(k), res.gyro_rotation.result.x));
  return res;
}

}  // namespace ldv::calib
