#include "sim/simulator.hpp"

#include <cmath>
#include <initializer_list>
#include <optional>
#include <set>

#include "common/io/input_error.hpp"
#include "common/io/number_text.hpp"
#include "common/time/gps_time.hpp"
#include "sim/effects.hpp"
#include "sim/gnss_model.hpp"
#include "sim/odometer_model.hpp"
#include "sim/random.hpp"
#include "sim/scenario.hpp"
#include "sim/truth_integrator.hpp"
#include "sim/vehicle_vibration.hpp"

namespace ldv::sim {
namespace {

void validate(const SimRequest& r) {
  auto fail = [](const std::string& opt, const std::string& msg) { throw InputError(opt, 0, msg); };
  if (!(r.duration_s > 0 && r.duration_s < kSecondsPerWeek))
    fail("--duration",
         "expected a positive number of seconds below one GPS week (604800), found " + six_significant(r.duration_s));
  if (!(r.imu_rate_hz >= 1.0 && r.imu_rate_hz <= 4000.0))
    fail("--imu-rate", "expected an IMU rate in [1, 4000] Hz, found " + six_significant(r.imu_rate_hz));
  if (!(r.gnss_rate_hz > 0.0 && r.gnss_rate_hz <= 50.0))
    fail("--gnss-rate", "expected a GNSS rate in (0, 50] Hz, found " + six_significant(r.gnss_rate_hz));
  if (r.gnss_rate_hz > r.imu_rate_hz) fail("--gnss-rate", "expected a GNSS rate not above the IMU rate");
  if (r.gps_week < 0 || r.gps_week > 9999)
    fail("--gps-week", "expected a GPS week in [0, 9999], found " + std::to_string(r.gps_week));
  if (!(r.start_sow_s >= 0.0 && r.start_sow_s + r.duration_s < kSecondsPerWeek))
    fail("--start-sow", "expected the run to stay within one GPS week: start " + six_significant(r.start_sow_s) +
                            " s + duration " + six_significant(r.duration_s) + " s must be below 604800 s");
  for (const Outage& o : r.outages)
    if (!(o.start_s >= 0.0) || !(o.length_s > 0.0))
      fail("--outages", "expected START:LENGTH with START >= 0 and LENGTH > 0 seconds, found " +
                            six_significant(o.start_s) + ":" + six_significant(o.length_s));
  if (!(r.gnss_latency_s >= 0.0 && r.gnss_latency_s < 10.0))
    fail("--gnss-latency", "expected a latency in [0, 10) s, found " + six_significant(r.gnss_latency_s));
  if (!(r.oscillator_hz >= 1e3 && r.oscillator_hz <= 1e9))
    fail("--osc-hz", "expected a counter frequency in [1e3, 1e9] Hz, found " + six_significant(r.oscillator_hz));
  if (!(std::abs(r.oscillator_ppm) <= 1000.0))
    fail("--osc-ppm", "expected a frequency error within +-1000 ppm, found " + six_significant(r.oscillator_ppm));
}

// Effects by name (SI); declared ones marked. Rejects an effect given twice.
struct EffectSet {
  std::map<std::string, EffectValue> values;
  std::set<std::string> declared;

  bool has(const std::string& n) const { return values.count(n) > 0; }
  Vec3 vec3(const std::string& n) const {
    const auto it = values.find(n);
    if (it == values.end()) return Vec3::Zero();
    return Vec3(it->second.si[0], it->second.si[1], it->second.si[2]);
  }
  double scalar(const std::string& n) const {
    const auto it = values.find(n);
    return it == values.end() ? 0.0 : it->second.si[0];
  }
};

EffectSet parse_effects(const SimRequest& r) {
  EffectSet set;
  for (const auto& spec : r.effects)
    for (auto& v : parse_effect(spec, "--effect")) {
      if (set.has(v.name)) throw InputError("--effect", 0, "effect '" + v.name + "' is given twice");
      set.values[v.name] = v;
    }
  for (const auto& spec : r.declared_effects)
    for (auto& v : parse_effect(spec, "--declare")) {
      if (!set.has(v.name)) {
        set.values[v.name] = v;
      } else if (!v.defaulted && set.values[v.name].engineering != v.engineering) {
        throw InputError("--declare", 0, "effect '" + v.name + "' is declared with values different from --effect");
      }
      set.declared.insert(v.name);
    }
  return set;
}

Vec3 draw(Rng& rng, const Vec3& std) {
  return Vec3(std.x() * rng.normal(), std.y() * rng.normal(), std.z() * rng.normal());
}

// The sensor model of one triad from the grade and the effects with this prefix ("gyro"/"accel").
// The grade's non-orthogonality is drawn from its own stream (`non_orthogonality`), after the turn-on bias and
// scale of both triads, so adding it left those draws unchanged.
TriadSensorModel triad_model(const TriadErrorModel& g, const EffectSet& fx, const std::string& prefix, Rng& turn_on,
                             Rng& non_orthogonality) {
  TriadSensorModel m;
  m.bias = draw(turn_on, g.turn_on_bias_std) + fx.vec3(prefix + "_bias");
  m.scale = draw(turn_on, g.scale_std) + fx.vec3(prefix + "_scale");
  m.misalignment_rad = draw(non_orthogonality, g.non_orthogonality_std) + fx.vec3(prefix + "_misalignment");
  m.nonlinear = fx.vec3(prefix + "_nonlinear_scale");
  m.white_N = g.white_N;
  m.quantization_Q = g.quantization_Q;
  m.quantization_rounding = g.quantization_rounding;
  m.rate_rw_K = g.rate_rw_K;
  m.ramp_R = g.ramp_R;
  m.sinusoid_amplitude = g.sinusoid_amplitude;
  m.sinusoid_hz = g.sinusoid_hz;
  if (!g.instability_B.isZero()) m.gauss_markov.push_back({g.instability_B, g.instability_T_s});
  const auto it = fx.values.find(prefix + "_moving_bias");
  if (it != fx.values.end()) {
    const auto& v = it->second.si;  // constant, B, T, K, R (same on every axis)
    m.bias += Vec3::Constant(v[0]);
    m.gauss_markov.push_back({Vec3::Constant(v[1]), Vec3::Constant(v[2])});
    m.rate_rw_K = (m.rate_rw_K.cwiseAbs2() + Vec3::Constant(v[3] * v[3])).cwiseSqrt();  // independent walks add
    m.ramp_R += Vec3::Constant(v[4]);
  }
  return m;
}

std::vector<double> as_vector(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

// The vehicle effects that are on, SI (units: find_realism_quantity / effect_table).
void record_vehicle_effects(const VehicleRealism& v, const ImuGrade& grade, double odometer_scale, bool scale_given,
                            SimResult& res) {
  auto& e = res.injected_effects;
  if (v.vibration_factor > 0.0) {
    e["vibration_white_factor"] = {v.vibration_factor};
    e["installed_arw"] = as_vector(grade.gyro.white_N * v.vibration_factor);
    e["installed_vrw"] = as_vector(grade.accel.white_N * v.vibration_factor);
    const EngineFrequencyLaw law = VehicleVibration::law();
    e["engine_vibration"] = {v.engine_accel_mps2, v.engine_gyro_rad_s, law.idle_hz, law.max_hz, law.speed_at_max_mps};
  }
  if (v.shocks_per_km > 0.0) {
    e["shocks"] = {v.shocks_per_km * 1e-3};
    e["shocks.count"] = {static_cast<double>(res.shocks.size())};
  }
  if (v.imu_latency_s > 0.0) e["imu_latency"] = {v.imu_latency_s};
  if (v.imu_stamp_jitter_s > 0.0) e["imu_stamp_jitter"] = {v.imu_stamp_jitter_s};
  if (v.mounted || v.odometer) e["vehicle_mounting"] = as_vector(v.mounting_rpy_rad);
  if (v.gnss_velocity_lag_s > 0.0) e["gnss_velocity_lag"] = {v.gnss_velocity_lag_s};
  if (v.gnss_velocity_noise_factor != 1.0) e["gnss_velocity_noise_factor"] = {v.gnss_velocity_noise_factor};
  if (v.gnss_outlier_rate > 0.0) {
    e["gnss_outliers"] = {v.gnss_outlier_rate};
    e["gnss_outliers.count"] = {static_cast<double>(res.gnss_outliers.size())};
  }
  if (v.odometer || scale_given) e["odometer_scale"] = {odometer_scale};
  if (v.odometer) {
    e["odometer_lever_arm"] = as_vector(v.odo_lever_arm_b_m);
    e["odometer_noise"] = {res.request.with_noise ? v.odo_noise_mps : 0.0};
    e["odometer_quantum"] = {v.odo_quantum_mps};
  }
  if (v.wheel_slip_rad_per_mps2 != 0.0) e["wheel_slip"] = {v.wheel_slip_rad_per_mps2};
}

// Mean of B's time constants over the axes of these triads that have a B; 1 h when none has one.
double mean_gm_time_s(std::initializer_list<const TriadErrorModel*> triads) {
  double sum = 0;
  int count = 0;
  for (const TriadErrorModel* t : triads)
    for (int i = 0; i < 3; ++i)
      if (t->instability_B[i] > 0) sum += t->instability_T_s[i], ++count;
  return count > 0 ? sum / count : 3600.0;
}

// A YAML list written on one line ([a, b, c]).
template <typename Values>
YAML::Node flow_list(const Values& values) {
  YAML::Node n(YAML::NodeType::Sequence);
  for (double x : values) n.push_back(x);
  n.SetStyle(YAML::EmitterStyle::Flow);
  return n;
}

}  // namespace

SimResult simulate(const SimRequest& req, const std::function<void(double)>& progress) {
  validate(req);
  const ImuGrade grade = req.custom_grade ? *req.custom_grade : imu_grade(req.grade);
  const EffectSet fx = parse_effects(req);
  const GnssErrorLevel gnss_level = gnss_error_level(req.gnss_mode);
  const Scenario scenario = load_scenario(req.scenario);
  const VehicleRealism veh = resolve_vehicle_options(req.vehicle, req.seed);
  MotionProfile motion = compile_scenario(scenario, req.duration_s);
  motion.mounted = veh.mounted;
  motion.C_b_v = veh.C_b_v;
  motion.slip_rad_per_mps2 = veh.wheel_slip_rad_per_mps2;

  SimResult res;
  res.request = req;
  res.realism = veh;
  res.grade_source = grade.source;
  res.scenario_name = scenario.name;
  res.declared_effects.assign(fx.declared.begin(), fx.declared.end());
  const double dt = 1.0 / req.imu_rate_hz;
  const size_t n = static_cast<size_t>(std::llround(req.duration_s * req.imu_rate_hz));
  if (n < 2) throw InputError("--duration", 0, "expected at least two IMU intervals at this rate");

  // Sensor model: grade draws first (so their values do not depend on which effects are present).
  Rng turn_on(req.seed, "turn_on"), non_orthogonality(req.seed, "non_orthogonality");
  ImuSensorModel sensor;
  sensor.gyro = triad_model(grade.gyro, fx, "gyro", turn_on, non_orthogonality);
  sensor.accel = triad_model(grade.accel, fx, "accel", turn_on, non_orthogonality);
  sensor.g_sensitivity = fx.vec3("g_sensitivity");
  sensor.with_noise = req.with_noise;

  // Gravity anomaly per IMU interval: constant, or Gauss-Markov in the n frame.
  std::vector<Vec3> anomaly;
  if (fx.has("gravity_anomaly")) {
    const auto& v = fx.values.at("gravity_anomaly").si;
    const Vec3 level(v[0], v[1], v[2]);
    anomaly.assign(n, level);
    if (v.size() == 4) {
      Rng rng(req.seed, "gravity_anomaly");
      const double phi = std::exp(-dt / v[3]), q = std::sqrt(1.0 - phi * phi);
      Vec3 x = draw(rng, level);
      for (size_t k = 0; k < n; ++k) {
        anomaly[k] = x;
        for (int i = 0; i < 3; ++i) x[i] = phi * x[i] + level[i] * q * rng.normal();
      }
      res.injected_effects["gravity_anomaly"] = as_vector(anomaly.front());
      res.injected_effects["gravity_anomaly.sigma"] = as_vector(level);
      res.injected_effects["gravity_anomaly.tau_s"] = {v[3]};
    } else {
      res.injected_effects["gravity_anomaly"] = as_vector(level);
    }
  }

  // Truth and exact increments.
  TruthOptions topt;
  topt.t0_sow_s = req.start_sow_s;
  topt.dt_s = dt;
  topt.intervals = n;
  topt.with_squares = sensor.gyro.any_nonlinear() || sensor.accel.any_nonlinear();
  topt.gravity_anomaly_n = &anomaly;
  TruthRun run = integrate_truth(motion, topt, [&](double f) {
    if (progress) progress(0.85 * f);
  });

  // The car's vibration and road bumps reach the sensor before its own errors do.
  std::optional<VehicleVibration> vibration;
  if (veh.vibration_factor > 0.0) vibration.emplace(veh, grade, dt, run.truth.front().vel_n_mps.norm(), req.seed);
  res.shocks = draw_shocks(run.truth, dt, veh.shocks_per_km, req.seed);
  RoadShocks shocks(res.shocks, veh.C_b_v);

  // Sensor errors.
  ImuErrorSimulator errors(sensor, req.seed);
  res.imu.resize(n);
  const size_t per_second = std::max<size_t>(1, static_cast<size_t>(std::llround(req.imu_rate_hz)));
  static const Vec3 kZero = Vec3::Zero();
  const double time_offset_s = fx.scalar("time_offset");  // GNSS tag minus IMU tag
  for (size_t k = 0; k < n; ++k) {
    const double t_mid = (static_cast<double>(k) + 0.5) * dt;
    if (k % per_second == 0) {
      ImuBiasSample b = errors.current_bias(static_cast<double>(k) * dt);
      b.t_s += req.start_sow_s;
      res.imu_bias_history.push_back(b);
    }
    ImuIncrement sensed = run.increments[k];
    if (vibration) vibration->add(sensed, run.truth[k + 1].vel_n_mps.norm());
    if (!res.shocks.empty()) shocks.add(sensed, static_cast<double>(k) * dt, static_cast<double>(k + 1) * dt);
    res.imu[k] = errors.apply(sensed, t_mid, topt.with_squares ? run.omega_sq_integral[k] : kZero,
                              topt.with_squares ? run.f_sq_integral[k] : kZero);
    // A late IMU: its time tag is the true sample time plus the latency. A time_offset (GNSS tag minus IMU tag) is
    // the IMU's too: the GNSS tags are GPS time, as a receiver's solution epochs are, and the truth is on them.
    res.imu[k].t_s += veh.imu_latency_s - time_offset_s;
    if (progress && k % (n / 10 + 1) == 0) progress(0.85 + 0.1 * k / n);
  }
  if (veh.imu_stamp_jitter_s > 0.0) {
    // A host that tags each sample off its sampling instant (uniform, +-sqrt(3) std) and integrates the sample's
    // rate over the interval between its tag and the one before: what estimator/calibrate/imu_stamp_jitter finds.
    Rng rng(req.seed, "imu_stamp_jitter");
    const double half_width_s = std::sqrt(3.0) * veh.imu_stamp_jitter_s;
    if (half_width_s >= 0.5 * dt)
      throw InputError("--imu-stamp-jitter", 0,
                       "a std below " + std::to_string(0.5 * dt / std::sqrt(3.0)) +
                           " s at this IMU rate (tags further off than half an interval would fall out of order)");
    double tag_before_s = res.imu.empty() ? 0.0 : res.imu.front().t_s - res.imu.front().dt_s;
    for (ImuIncrement& s : res.imu) {
      const double tag_s = s.t_s + half_width_s * (2.0 * rng.uniform() - 1.0), dt_s = tag_s - tag_before_s;
      s.dtheta_b_rad *= dt_s / s.dt_s;
      s.dvel_b_mps *= dt_s / s.dt_s;
      s.t_s = tag_s;
      s.dt_s = dt_s;
      tag_before_s = tag_s;
    }
  }

  // GNSS.
  GnssSchedule sch;
  sch.rate_hz = req.gnss_rate_hz;
  for (const Outage& o : req.outages) sch.outages.push_back({o.start_s, o.length_s});
  sch.lever_arm_b_m = fx.vec3("lever_arm");
  sch.latency_mean_s = req.gnss_latency_s;
  sch.with_velocity = req.gnss_velocity;
  sch.with_noise = req.with_noise;
  sch.velocity_lag_s = veh.gnss_velocity_lag_s;
  sch.velocity_noise_factor = veh.gnss_velocity_noise_factor;
  sch.outlier_rate = veh.gnss_outlier_rate;
  GnssRun gnss = simulate_gnss(motion, run.truth, dt, gnss_level, sch, req.seed);
  res.gnss = std::move(gnss.fixes);
  res.gnss_latency_s = std::move(gnss.latency_s);
  res.gnss_outliers = std::move(gnss.outliers);

  // Odometer: scale from --effect odometer_scale, else the realism preset's draw (N(0, 0.5 %)).
  double odometer_scale = fx.scalar("odometer_scale");
  if (!fx.has("odometer_scale") && veh.realism_vehicle) {
    Rng rng(req.seed, "realism_odometer_scale");
    odometer_scale = 0.005 * rng.normal();
  }
  if (veh.odometer) {
    OdometerModel od;
    od.rate_hz = veh.odo_rate_hz;
    od.lever_arm_b_m = veh.odo_lever_arm_b_m;
    od.scale = odometer_scale;
    od.noise_mps = veh.odo_noise_mps;
    od.quantum_mps = veh.odo_quantum_mps;
    od.with_noise = req.with_noise;
    res.odometer = simulate_odometer(motion, run.truth, dt, od, req.seed);
  }
  res.truth = std::move(run.truth);

  // True values of the injected effects (SI).
  auto record_if = [&](const std::string& name, const Vec3& v) {
    if (fx.has(name) || !v.isZero()) res.injected_effects[name] = as_vector(v);
  };
  record_if("gyro_bias", sensor.gyro.bias);
  record_if("accel_bias", sensor.accel.bias);
  record_if("gyro_scale", sensor.gyro.scale);
  record_if("accel_scale", sensor.accel.scale);
  record_if("gyro_misalignment", sensor.gyro.misalignment_rad);  // the grade's draw plus the injected effect
  record_if("accel_misalignment", sensor.accel.misalignment_rad);
  for (const char* name : {"g_sensitivity", "gyro_nonlinear_scale",
                           "accel_nonlinear_scale", "lever_arm", "time_offset", "gyro_moving_bias",
                           "accel_moving_bias"})
    if (fx.has(name)) res.injected_effects[name] = fx.values.at(name).si;
  record_vehicle_effects(veh, grade, odometer_scale, fx.has("odometer_scale"), res);

  // KF-GINS configuration: initial state from the truth, noise from the grade, declared effects only.
  KfGinsConfig& c = res.kfgins;
  c.imu_rate_hz = req.imu_rate_hz;
  // As KF-GINS reads it: the initial state holds at the first IMU record at or after starttime, whose own
  // increment is not integrated. So starttime is the first record's epoch and the state is the truth there
  // (KF-GINS refuses a starttime before its first record).
  c.start_time_s = res.imu.empty() ? req.start_sow_s : res.imu.front().t_s;
  c.end_time_s = -1.0;
  const TruthSample& t0 = res.truth.size() > 1 ? res.truth[1] : res.truth.front();
  c.init_pos = t0.pos;
  c.init_vel_n_mps = t0.vel_n_mps;
  c.init_rpy_rad = t0.rpy_rad;
  c.init_pos_std_ned_m = res.gnss.empty() ? Vec3::Constant(0.01) : res.gnss.front().pos_std_ned_m;
  c.init_vel_std_n_mps = Vec3::Constant(0.01);
  // The gyros' Q is a white error e_k of the integrated angle, stationary from the start: the attitude the filter
  // integrates from this truth carries e_k - e_1, a constant tilt of std Q beside the white part. (With 0.01 deg
  // stated and the 3DM-GX2's printed 0.18 deg, the filter rejected every fix of a standing run and ran away.)
  const Vec3& q_gyro = grade.gyro.quantization_Q;
  const double q_level = std::max(q_gyro.x(), q_gyro.y());
  const Vec3 att_std_rad = Vec3(0.01, 0.01, 0.05) * kDegToRad;
  c.init_att_std_rad = (att_std_rad.cwiseAbs2() + Vec3(q_level, q_level, q_gyro.z()).cwiseAbs2()).cwiseSqrt();
  auto& nz = c.imu_noise;
  nz.arw_rad_per_sqrt_s = grade.gyro.white_N;
  nz.vrw_mps_per_sqrt_s = grade.accel.white_N;
  // The bias as KF-GINS models it: a first-order Gauss-Markov process with the in-run terms (bias instability
  // B, and the rate random walk K as a Gauss-Markov of the same driving noise: q = 2 sigma^2 / T = K^2), and
  // the turn-on bias as the initial std on top (initbgstd / initbastd). Merged into the process (the old way)
  // the turn-on bias made the filter expect the bias to wander by it within T: a MEMS IMU's outage drift came
  // out 2-3.5x worse than its own terms imply, and the non-holonomic constraint then traded the vertical
  // velocity for pitch (a 60 s outage 4x worse with NHC than without).
  // KF-GINS has one correlation time for both triads: the mean of B's time constants over every axis of the
  // gyro and the accelerometer that has a B (the paper's grades have per-axis T: hg1700 160 s from the
  // accelerometer alone, hg1900 109 s, 3dm-gx2 50 s); 1 h when no axis has a B.
  nz.corr_time_s = mean_gm_time_s({&grade.gyro, &grade.accel});
  const auto in_run = [&](const TriadErrorModel& s) {
    Vec3 std;
    for (int i = 0; i < 3; ++i) std(i) = kfgins_single_bias_std(s.instability_B(i), s.rate_rw_K(i), nz.corr_time_s);
    return std;
  };
  nz.gyro_bias_std_rad_s = in_run(grade.gyro);
  nz.accel_bias_std_mps2 = in_run(grade.accel);
  c.init_gyro_bias_std_rad_s = (grade.gyro.turn_on_bias_std.cwiseAbs2() + nz.gyro_bias_std_rad_s.cwiseAbs2()).cwiseSqrt();
  c.init_accel_bias_std_mps2 = (grade.accel.turn_on_bias_std.cwiseAbs2() + nz.accel_bias_std_mps2.cwiseAbs2()).cwiseSqrt();
  nz.gyro_scale_std = grade.gyro.scale_std;
  nz.accel_scale_std = grade.accel.scale_std;
  const auto declared = [&](const std::string& n) { return fx.declared.count(n) > 0; };
  if (declared("gyro_bias")) c.init_gyro_bias_rad_s = fx.vec3("gyro_bias");
  if (declared("accel_bias")) c.init_accel_bias_mps2 = fx.vec3("accel_bias");
  if (declared("gyro_scale")) c.init_gyro_scale = fx.vec3("gyro_scale");
  if (declared("accel_scale")) c.init_accel_scale = fx.vec3("accel_scale");
  if (declared("lever_arm")) c.antenna_lever_b_m = fx.vec3("lever_arm");
  YAML::Node ldv;
  ldv["simulator"]["grade"] = grade.name;
  ldv["simulator"]["seed"] = req.seed;
  ldv["simulator"]["scenario"] = scenario.name;
  ldv["gnss_latency_s"] = req.gnss_latency_s;
  // geoldv51's moving bias per term (estimator/run/run_navigation.cpp): B with its time constant (the triad's
  // mean over the axes that have one), K, |R|, SI.
  const auto write_terms = [&](const TriadErrorModel& t, const std::string& prefix, const char* gm, const char* rw,
                               const char* ramp) {
    ldv[prefix + gm] = flow_list(t.instability_B);
    ldv[prefix + "gm_time_s"] = mean_gm_time_s({&t});
    ldv[prefix + rw] = flow_list(t.rate_rw_K);
    ldv[prefix + ramp] = flow_list(t.ramp_R.cwiseAbs().eval());
  };
  write_terms(grade.gyro, "moving_bias_gyro_", "gm_rad_s", "rw_rad_s_sqrt_s", "ramp_rad_s2");
  write_terms(grade.accel, "moving_bias_accel_", "gm_mps2", "rw_mps2_sqrt_s", "ramp_mps3");
  // The gyros' Allan Q (white error of the integrated angle [rad]): the filter adds its tilt of the specific force.
  if (grade.gyro.quantization_Q.any()) ldv["gyro_quantization_rad"] = flow_list(grade.gyro.quantization_Q);
  for (const auto& name : fx.declared) {
    const YAML::Node seq = flow_list(fx.values.at(name).si);
    ldv["declared_effects_si"][name] = seq;
  }
  c.ldv = ldv;
  if (progress) progress(1.0);
  return res;
}

}  // namespace ldv::sim
