#include "estimator/options.hpp"

#include <algorithm>
#include <ostream>
#include <stdexcept>

#include "estimator/effects/registry.hpp"

namespace ldv::est {

FilterOptions::FilterOptions() {
  // Defaults of a tactical-grade IMU (HG1700-like); run_kfgins overrides them from the KF-GINS config.
  const double deg_h = kDegToRad / 3600.0;
  gyro_bias = {Vec3::Zero(), Vec3::Constant(1.0 * deg_h), BlockOptions::Process::kGaussMarkov,
               Vec3::Constant(1.0 * deg_h), 3600.0, Vec3::Zero()};
  accel_bias = {Vec3::Zero(), Vec3::Constant(1e-3 * 9.8), BlockOptions::Process::kGaussMarkov,
                Vec3::Constant(1e-3 * 9.8), 3600.0, Vec3::Zero()};
  gyro_scale = {Vec3::Zero(), Vec3::Constant(300e-6), BlockOptions::Process::kGaussMarkov,
                Vec3::Constant(300e-6), 3600.0, Vec3::Zero()};
  accel_scale = gyro_scale;
  gyro_misalignment = {Vec3::Zero(), Vec3::Constant(100e-6), BlockOptions::Process::kConstant, Vec3::Zero(), 3600.0, Vec3::Zero()};
  accel_misalignment = gyro_misalignment;
  g_sensitivity = {Vec3::Zero(), Vec3::Constant(1.0 * deg_h / 9.8), BlockOptions::Process::kConstant, Vec3::Zero(), 3600.0, Vec3::Zero()};
  lever_arm = {Vec3::Zero(), Vec3::Constant(0.05), BlockOptions::Process::kConstant, Vec3::Zero(), 3600.0, Vec3::Zero()};
  // Gravity disturbance: ~30 mGal over ~1000 s (a few km at driving speed).
  gravity_anomaly = {Vec3::Zero(), Vec3::Constant(30e-5), BlockOptions::Process::kGaussMarkov,
                     Vec3::Constant(30e-5), 1000.0, Vec3::Zero()};
  // Slowly varying RTK-fixed error (multipath, residual troposphere): ~1 cm horizontal, 1.5 cm vertical, 60 s.
  gnss_position_bias = {Vec3::Zero(), Vec3(0.008, 0.008, 0.015), BlockOptions::Process::kGaussMarkov,
                        Vec3(0.008, 0.008, 0.015), 60.0, Vec3::Zero()};
  gyro_moving_bias = {Vec3::Constant(1.0 * deg_h), Vec3::Constant(0.5 * deg_h), 3600.0,
                      Vec3::Constant(0.01 * deg_h), Vec3::Constant(0.01 * deg_h / 3600.0)};
  accel_moving_bias = {Vec3::Constant(1e-3 * 9.8), Vec3::Constant(0.5e-3 * 9.8), 3600.0,
                       Vec3::Constant(1e-6), Vec3::Constant(1e-8)};
}

namespace {
const char* process_name(BlockOptions::Process p) {
  switch (p) {
    case BlockOptions::Process::kConstant: return "constant";
    case BlockOptions::Process::kRandomWalk: return "random walk";
    case BlockOptions::Process::kGaussMarkov: return "Gauss-Markov";
  }
  return "?";
}
void print_block(std::ostream& out, const char* name, const BlockOptions& b, double scale, const char* unit) {
  out << "  " << name << ": prior " << (b.init * scale).transpose() << " +- " << (b.init_std * scale).transpose()
      << " " << unit << ", " << process_name(b.process);
  if (b.process == BlockOptions::Process::kGaussMarkov)
    out << " sigma " << (b.sigma * scale).transpose() << " " << unit << " T " << b.corr_time_s << " s";
  if (b.process == BlockOptions::Process::kRandomWalk)
    out << " " << (b.rw_density * scale).transpose() << " " << unit << "/sqrt(s)";
  out << "\n";
}
}  // namespace

void FilterOptions::print(std::ostream& out) const {
  const double deg_h = kDegToRad / 3600.0;
  out << "model " << model;
  for (const auto& a : add) out << " +" << a;
  for (const auto& d : drop) out << " -" << d;
  out << "\n  arw " << (arw_rad_per_sqrt_s / (kDegToRad / 60.0)).transpose() << " deg/sqrt(h), vrw "
      << (vrw_mps_per_sqrt_s * 60.0).transpose() << " m/s/sqrt(h)\n";
  print_block(out, "gyro_bias", gyro_bias, 1.0 / deg_h, "deg/h");
  print_block(out, "accel_bias", accel_bias, 1e5, "mGal");
  print_block(out, "gyro_scale", gyro_scale, 1e6, "ppm");
  print_block(out, "accel_scale", accel_scale, 1e6, "ppm");
  print_block(out, "lever_arm", lever_arm, 1.0, "m");
  print_block(out, "gravity_anomaly", gravity_anomaly, 1e5, "mGal");
  print_block(out, "gnss_position_bias", gnss_position_bias, 1e2, "cm");
  out << "  covariance period " << cov_period_s << " s, gate probability " << gate_probability
      << ", GNSS velocity " << (use_gnss_velocity ? "used" : "ignored") << ", ZUPT "
      << (zupt.enabled ? "on" : "off") << ", late-measurement horizon " << history_s << " s\n";
}

std::vector<std::string> resolve_model(const std::string& model, const std::vector<std::string>& add,
                                       const std::vector<std::string>& drop) {
  std::vector<std::string> effects;
  if (model == "ins15") {
    effects = {"gyro_bias", "accel_bias"};
  } else if (model == "kfgins21") {
    effects = {"gyro_bias", "accel_bias", "gyro_scale", "accel_scale"};
  } else if (model == "geoldv51") {
    // 12 navigation states = position, velocity, attitude + the GNSS lever arm.
    effects = {"lever_arm", "gravity_anomaly", "gyro_scale", "accel_scale", "gyro_moving_bias", "accel_moving_bias"};
  } else {
    throw std::invalid_argument("unknown model '" + model + "' (expected ins15, kfgins21 or geoldv51)");
  }
  auto expand = [](const std::string& name) {
    // `moving_bias` is the vocabulary name for both sensors' blocks.
    if (name == "moving_bias") return std::vector<std::string>{"gyro_moving_bias", "accel_moving_bias"};
    if (!effect_registry().contains(name))
      throw std::invalid_argument("unknown effect '" + name + "' (known: " + effect_registry().names() + ")");
    return std::vector<std::string>{name};
  };
  for (const auto& a : add)
    for (const auto& e : expand(a))
      if (std::find(effects.begin(), effects.end(), e) == effects.end()) effects.push_back(e);
  for (const auto& d : drop)
    for (const auto& e : expand(d)) std::erase(effects, e);
  return effects;
}

}  // namespace ldv::est
