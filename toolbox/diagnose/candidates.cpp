#include "toolbox/diagnose/candidates.hpp"

#include <algorithm>

#include "estimator/effects/registry.hpp"

namespace ldv::diag {
namespace {

struct Screenable {
  const char* name;
  double plausible_si;     // per state
  const char* excitation;  // the manoeuvres that make it visible (how to separate it from its look-alikes)
};

// Constant-parameter effects of the vocabulary and the largest size any IMU/GNSS set-up plausibly has:
// a component whose minimal detectable size on this drive exceeds it cannot be tested here.
constexpr double kDegH = 3.141592653589793 / 180.0 / 3600.0;
const Screenable kScreenable[] = {
    {"lever_arm", 3.0, "turns and attitude changes"},  // m
    {"time_offset", 0.5, "speed changes and high speed"},  // s
    {"gyro_scale", 0.02, "large rotations (turns both ways for z, hills for y, banked roads for x)"},  // 20000 ppm
    {"accel_scale", 0.02, "strong acceleration and braking (x), fast turns (y), vertical motion (z)"},
    {"gyro_misalignment", 0.01, "rotation about one axis while pitched or banked"},  // rad (2000 arcsec)
    {"accel_misalignment", 0.01, "acceleration along one axis: braking, turns, hills"},
    {"g_sensitivity", 2000.0 * kDegH / 9.80665,
     "changes of specific force: hard acceleration and braking, hills"},  // 2000 deg/h/g (MEMS: ~0.1 deg/s/g)
    {"gravity_anomaly", 2e-3, "heading changes over a long distance"},  // 200 mGal
    {"gyro_bias", 1000.0 * kDegH, "heading changes and static periods"},  // only when dropped from the model
    {"accel_bias", 0.1, "heading changes and attitude changes"},
    // Seen only through the land-vehicle aids (screened when the aid is on).
    {"vehicle_mounting", 0.1, "steady speed (yaw, pitch) and turns (roll)"},  // rad (6 deg beyond the coarse mounting)
    {"odometer_scale", 0.05, "distance at steady speed"},  // 5 %
    {"odometer_lever_arm", 3.0, "turns at speed"},         // m
};

// Whether the measurements of this run see the effect at all: the vehicle-frame effects enter only the aids.
bool seen_with(const std::string& name, const est::AidOptions& aids) {
  if (name == "vehicle_mounting") return aids.has("nhc") || aids.has("odometer");
  if (name == "odometer_scale" || name == "odometer_lever_arm") return aids.has("odometer");
  return true;  // GNSS sees it
}

}  // namespace

est::BlockOptions* block_options(est::FilterOptions& o, const std::string& name) {
  if (name == "gyro_bias") return &o.gyro_bias;
  if (name == "accel_bias") return &o.accel_bias;
  if (name == "gyro_scale") return &o.gyro_scale;
  if (name == "accel_scale") return &o.accel_scale;
  if (name == "gyro_misalignment") return &o.gyro_misalignment;
  if (name == "accel_misalignment") return &o.accel_misalignment;
  if (name == "g_sensitivity") return &o.g_sensitivity;
  if (name == "lever_arm") return &o.lever_arm;
  if (name == "gravity_anomaly") return &o.gravity_anomaly;
  if (name == "vehicle_mounting") return &o.vehicle_mounting;
  if (name == "odometer_lever_arm") return &o.odometer_lever_arm;
  return nullptr;
}

void set_prior(est::FilterOptions& o, const std::string& name, const Eigen::VectorXd& value_si,
               const Eigen::VectorXd& std_si) {
  if (name == "time_offset") {
    o.time_offset_init_s = value_si(0);
    o.time_offset_std_s = std_si(0);
    return;
  }
  if (name == "odometer_scale") {
    o.odometer_scale_init = value_si(0);
    o.odometer_scale_std = std_si(0);
    return;
  }
  if (est::BlockOptions* b = block_options(o, name)) {
    b->init = value_si.head<3>();
    b->init_std = std_si.head<3>();
  }
}

CandidateSet make_candidates(const est::FilterOptions& options, const std::vector<std::string>& model_effects) {
  CandidateSet set;
  const est::EffectRegistry& reg = est::effect_registry();
  for (const Screenable& s : kScreenable) {
    if (std::find(model_effects.begin(), model_effects.end(), s.name) != model_effects.end()) continue;
    if (!seen_with(s.name, options.aids)) continue;
    Candidate c;
    c.name = s.name;
    c.effect = reg.make(s.name, options);
    c.dim = c.effect->dim();
    c.column = set.columns;
    c.state_names = c.effect->state_names();
    c.unit = c.effect->print_unit();
    c.assumed_si = Eigen::VectorXd::Zero(c.dim);
    // Outside the model the filter still applies the configured lever arm and time offset.
    if (c.name == "lever_arm") c.assumed_si = options.lever_arm.init;
    if (c.name == "time_offset") c.assumed_si(0) = options.time_offset_init_s;
    if (c.name == "vehicle_mounting") c.assumed_si = options.vehicle_mounting.init;
    if (c.name == "odometer_lever_arm") c.assumed_si = options.odometer_lever_arm.init;
    if (c.name == "odometer_scale") c.assumed_si(0) = options.odometer_scale_init;
    c.plausible_si = Eigen::VectorXd::Constant(c.dim, s.plausible_si);
    c.excitation = s.excitation;
    set.columns += c.dim;
    set.candidates.push_back(std::move(c));
  }
  // Every other registry block is a stochastic process, not a constant: the model check's NIS and
  // whiteness (and `ldv allan`) speak for it.
  for (const auto& entry : reg.entries) {
    const std::string name = entry.name;
    const bool screened = std::any_of(std::begin(kScreenable), std::end(kScreenable),
                                      [&](const Screenable& s) { return name == s.name; });
    if (!screened && std::find(model_effects.begin(), model_effects.end(), name) == model_effects.end())
      set.not_screened.push_back({name, "stochastic (Gauss-Markov / random walk / ramp): see the NIS and whiteness"});
  }
  return set;
}

}  // namespace ldv::diag
