#include "estimator/run/run_navigation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

#include "common/geo/earth_model.hpp"
#include "common/io/input_error.hpp"
#include "estimator/calibrate/imu_stamp_jitter.hpp"
#include "estimator/calibrate/installed_imu_noise.hpp"
#include "estimator/filter/nav_filter.hpp"
#include "estimator/ins/alignment.hpp"
#include "estimator/run/alignment_options_from.hpp"
#include "estimator/run/effect_priors_config.hpp"
#include "estimator/run/nav_session.hpp"
#include "estimator/update/updater.hpp"

namespace ldv::est {
namespace {

template <typename T>
T ldv_key(const KfGinsConfig& cfg, const char* key, T fallback) {
  if (!cfg.ldv.IsDefined() || cfg.ldv.IsNull() || !cfg.ldv[key]) return fallback;
  try {
    return cfg.ldv[key].as<T>();
  } catch (const YAML::Exception&) {
    throw InputError(cfg.config_path, cfg.ldv[key].Mark().line + 1, std::string("key 'ldv.") + key + "': wrong type");
  }
}

// ldv.gnss_variance_scale: one factor for every solution quality, or [fixed, float, other] (the numbers' range is
// checked at load, kfgins_config.cpp).
std::array<double, 3> gnss_variance_scale_from(const KfGinsConfig& cfg, std::array<double, 3> fallback) {
  if (!has_ldv_key(cfg, "gnss_variance_scale")) return fallback;
  const YAML::Node node = cfg.ldv["gnss_variance_scale"];
  if (!node.IsSequence()) {
    const double factor = ldv_key<double>(cfg, "gnss_variance_scale", 1.0);
    return {factor, factor, factor};
  }
  const auto v = ldv_key<std::vector<double>>(cfg, "gnss_variance_scale", {});
  if (v.size() != 3)
    throw InputError(cfg.config_path, node.Mark().line + 1,
                     "key 'ldv.gnss_variance_scale': expected one factor or three [fixed, float, other], found " +
                         std::to_string(v.size()));
  return {v[0], v[1], v[2]};
}

}  // namespace

double ldv_number(const KfGinsConfig& cfg, const char* key, double fallback) { return ldv_key<double>(cfg, key, fallback); }

void make_kfgins_compatible(FilterOptions& o, const KfGinsConfig& cfg) {
  o.robust_update = false;
  o.adapt_imu_noise = false;
  o.imu_stamp_jitter_from_tags = false;
  o.gate_measurements = false;
  o.measurement_snap_s = 1e-3;
  if (!has_ldv_key(cfg, "cov_period_s")) o.cov_period_s = 1e-6;
}

FilterOptions options_from_kfgins(const KfGinsConfig& cfg) {
  FilterOptions o;
  const KfGinsImuNoise& n = cfg.imu_noise;
  o.arw_rad_per_sqrt_s = n.arw_rad_per_sqrt_s;
  o.vrw_mps_per_sqrt_s = n.vrw_mps_per_sqrt_s;
  auto gm = [&](BlockOptions& b, const Vec3& init, const std::optional<Vec3>& init_std, const Vec3& sigma) {
    // KF-GINS: first-order Gauss-Markov with corrtime; prior std defaults to the process std.
    b.init = init;
    b.init_std = init_std.value_or(sigma);
    b.process = BlockOptions::Process::kGaussMarkov;
    b.sigma = sigma;
    b.corr_time_s = n.corr_time_s;
  };
  gm(o.gyro_bias, cfg.init_gyro_bias_rad_s, cfg.init_gyro_bias_std_rad_s, n.gyro_bias_std_rad_s);
  gm(o.accel_bias, cfg.init_accel_bias_mps2, cfg.init_accel_bias_std_mps2, n.accel_bias_std_mps2);
  gm(o.gyro_scale, cfg.init_gyro_scale, cfg.init_gyro_scale_std, n.gyro_scale_std);
  gm(o.accel_scale, cfg.init_accel_scale, cfg.init_accel_scale_std, n.accel_scale_std);
  o.gyro_moving_bias.constant_std = o.gyro_bias.init_std;
  o.gyro_moving_bias.gm_sigma = n.gyro_bias_std_rad_s;
  o.gyro_moving_bias.gm_corr_time_s = n.corr_time_s;
  o.accel_moving_bias.constant_std = o.accel_bias.init_std;
  o.accel_moving_bias.gm_sigma = n.accel_bias_std_mps2;
  o.accel_moving_bias.gm_corr_time_s = n.corr_time_s;
  o.lever_arm.init = cfg.antenna_lever_b_m;

  o.model = ldv_key<std::string>(cfg, "model", o.model);
  o.add = ldv_key<std::vector<std::string>>(cfg, "add", {});
  o.drop = ldv_key<std::vector<std::string>>(cfg, "drop", {});
  o.cov_period_s = ldv_key<double>(cfg, "cov_period_s", o.cov_period_s);
  o.gate_probability = ldv_key<double>(cfg, "gate_probability", o.gate_probability);
  o.use_gnss_velocity = ldv_key<bool>(cfg, "use_gnss_velocity", o.use_gnss_velocity);
  if (ldv_key<bool>(cfg, "kfgins_compatible", false)) make_kfgins_compatible(o, cfg);
  o.step_confirm_s = ldv_key<double>(cfg, "step_confirm_s", o.step_confirm_s);
  o.adapt_imu_noise = ldv_key<bool>(cfg, "adapt_imu_noise", o.robust_update && o.adapt_imu_noise);
  o.split_noise_adaptation = ldv_key<bool>(cfg, "split_noise_adaptation", o.split_noise_adaptation);
  // The time_offset effect's prior mean [s] (GNSS tag minus IMU tag), e.g. from `ldv diagnose --write-config`.
  o.time_offset_init_s = ldv_key<double>(cfg, "time_offset_s", o.time_offset_init_s);
  o.effect_priors = effect_priors_from(cfg);
  o.gnss_variance_scale = gnss_variance_scale_from(cfg, o.gnss_variance_scale);
  o.zupt.enabled = ldv_key<bool>(cfg, "zupt", o.zupt.enabled);
  o.aids.enabled = ldv_key<std::vector<std::string>>(cfg, "aids", o.aids.enabled);
  for (const std::string& aid : o.aids.enabled)
    if (!is_aid_name(aid))
      throw InputError(cfg.config_path, cfg.ldv["aids"].Mark().line + 1,
                       "key 'ldv.aids': unknown aid '" + aid + "' (expected " + aid_name_list() + ")");
  const auto vec3_key = [&](const char* key, Vec3 fallback, double scale) -> Vec3 {
    if (!has_ldv_key(cfg, key)) return fallback;
    const auto v = ldv_key<std::vector<double>>(cfg, key, {});
    if (v.size() != 3 || !std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2]))
      throw InputError(cfg.config_path, cfg.ldv[key].Mark().line + 1,
                       std::string("key 'ldv.") + key + "': expected a list of 3 finite numbers");
    return Vec3(v[0], v[1], v[2]) * scale;
  };
  o.aids.mounting_rpy_rad = vec3_key("vehicle_mounting_deg", o.aids.mounting_rpy_rad, kDegToRad);
  o.odometer_lever_arm.init = vec3_key("odometer_lever_arm_m", o.odometer_lever_arm.init, 1.0);
  o.gyro_quantization_rad = vec3_key("gyro_quantization_rad", o.gyro_quantization_rad, 1.0);
  o.imu_stamp_jitter_s = ldv_key<double>(cfg, "imu_stamp_jitter_s", o.imu_stamp_jitter_s);
  if (has_ldv_key(cfg, "imu_stamp_jitter_s")) o.imu_stamp_jitter_from_tags = false;
  // geoldv51's moving bias per term, where the configuration has them (ldv sim writes the grade's): the
  // Gauss-Markov is B alone (imunoise's gbstd merges K into it), K drives the random-walk states, R is the
  // ramp rate's prior. Each key is optional.
  for (auto [mb, prefix] : {std::pair{&o.gyro_moving_bias, std::string("moving_bias_gyro_")},
                            std::pair{&o.accel_moving_bias, std::string("moving_bias_accel_")}}) {
    const bool gyro = prefix == "moving_bias_gyro_";
    mb->gm_sigma = vec3_key((prefix + (gyro ? "gm_rad_s" : "gm_mps2")).c_str(), mb->gm_sigma, 1.0);
    mb->rw_density = vec3_key((prefix + (gyro ? "rw_rad_s_sqrt_s" : "rw_mps2_sqrt_s")).c_str(), mb->rw_density, 1.0);
    mb->ramp_rate_std = vec3_key((prefix + (gyro ? "ramp_rad_s2" : "ramp_mps3")).c_str(), mb->ramp_rate_std, 1.0);
    mb->gm_corr_time_s = ldv_key<double>(cfg, (prefix + "gm_time_s").c_str(), mb->gm_corr_time_s);
  }
  o.aids.nhc_std_mps = ldv_key<double>(cfg, "nhc_std_mps", o.aids.nhc_std_mps);
  o.aids.odometer_std_mps = ldv_key<double>(cfg, "odometer_std_mps", o.aids.odometer_std_mps);
  o.odometer_scale_init = ldv_key<double>(cfg, "odometer_scale", o.odometer_scale_init);
  o.history_s = ldv_key<double>(cfg, "history_s", 0.0);  // offline: fixes are never late
  o.align_speed_mps = ldv_key<double>(cfg, "align_speed_mps", o.align_speed_mps);
  o.align_hypotheses = ldv_key<int>(cfg, "align_hypotheses", o.robust_update ? o.align_hypotheses : 1);
  if (!(o.align_speed_mps > 0) || o.align_hypotheses < 1 || o.align_hypotheses > 360)
    throw InputError(cfg.config_path, cfg.ldv["align_speed_mps"] ? cfg.ldv["align_speed_mps"].Mark().line + 1 : 0,
                     "keys 'ldv.align_speed_mps' (> 0 m/s) and 'ldv.align_hypotheses' (1..360): out of range");
  // gnss_position_bias (used when the model includes it): sigma [m] as one number or [N, E, D], tau [s].
  if (cfg.ldv.IsDefined() && !cfg.ldv.IsNull() && cfg.ldv["gnss_bias_sigma_m"]) {
    const YAML::Node node = cfg.ldv["gnss_bias_sigma_m"];
    Vec3 sigma;
    if (node.IsSequence()) {
      const auto v = ldv_key<std::vector<double>>(cfg, "gnss_bias_sigma_m", {});
      if (v.size() != 3 || !(v[0] > 0 && v[1] > 0 && v[2] > 0))
        throw InputError(cfg.config_path, node.Mark().line + 1,
                         "key 'ldv.gnss_bias_sigma_m': expected a positive number or a list of 3 (N E D) [m]");
      sigma = Vec3(v[0], v[1], v[2]);
    } else {
      const double s = ldv_key<double>(cfg, "gnss_bias_sigma_m", 0.0);
      if (!(s > 0))
        throw InputError(cfg.config_path, node.Mark().line + 1, "key 'ldv.gnss_bias_sigma_m': must be positive [m]");
      sigma = Vec3::Constant(s);
    }
    o.gnss_position_bias.sigma = sigma;
    o.gnss_position_bias.init_std = sigma;
  }
  o.gnss_position_bias.corr_time_s = ldv_key<double>(cfg, "gnss_bias_tau_s", o.gnss_position_bias.corr_time_s);
  if (!(o.gnss_position_bias.corr_time_s > 0))
    throw InputError(cfg.config_path, cfg.ldv["gnss_bias_tau_s"].Mark().line + 1,
                     "key 'ldv.gnss_bias_tau_s': must be positive [s]");
  return o;
}

namespace {
size_t first_imu_index(const std::vector<ImuIncrement>& imu, const KfGinsConfig& cfg) {
  const double t0 = cfg.start_time_s, t1 = cfg.end_time_s < 0 ? 1e300 : cfg.end_time_s;
  auto first = std::lower_bound(imu.begin(), imu.end(), t0, [](const ImuIncrement& a, double t) { return a.t_s < t; });
  const size_t i = static_cast<size_t>(first - imu.begin());
  if (i >= imu.size() || imu[i].t_s > t1) throw InputError(cfg.imu_path, 0, "no IMU samples between starttime and endtime");
  return i;
}

std::string could_not_align(const SessionOptions& so) {
  char b[64];
  std::snprintf(b, sizeof b, "%.1f", std::min(so.alignment.speed_min_mps, NavSession::kSlowCourseSpeed_mps));
  return std::string("could not align: no static period with usable gyros and no GNSS speed above ") + b +
         " m/s (give initpos/initvel/initatt in the configuration)";
}
}  // namespace

SessionOptions session_options_from(const KfGinsConfig& cfg, const FilterOptions& filter,
                                    const AlignmentOptions* alignment) {
  SessionOptions so;
  so.filter = filter;
  so.alignment = alignment ? *alignment : alignment_options_from(filter);
  if (cfg.init_pos && cfg.init_vel_n_mps && cfg.init_rpy_rad) {
    NavState s;
    s.pos = *cfg.init_pos;
    s.v_n_mps = *cfg.init_vel_n_mps;
    s.q_b_n = quat_from_euler(*cfg.init_rpy_rad);
    NavStd sd;
    sd.pos_ned_m = cfg.init_pos_std_ned_m;
    sd.vel_n_mps = cfg.init_vel_std_n_mps;
    sd.att_rad = cfg.init_att_std_rad;
    so.given_start = std::make_pair(s, sd);
  }
  so.start_time_s = cfg.start_time_s;
  so.end_time_s = cfg.end_time_s < 0 ? 1e300 : cfg.end_time_s;
  return so;
}

bool imu_latency_wanted(const KfGinsConfig& cfg, const FilterOptions& filter, const std::string& requested,
                        bool shift_given) {
  std::string mode = requested;
  if (mode.empty()) {
    mode = ldv_key<std::string>(cfg, "imu_latency", "auto");
    if (shift_given || !filter.robust_update) mode = "off";
  }
  if (mode != "auto" && mode != "off") {
    const int line = has_ldv_key(cfg, "imu_latency") && requested.empty() ? cfg.ldv["imu_latency"].Mark().line + 1 : 0;
    throw InputError(cfg.config_path, line, "imu_latency '" + mode + "': expected auto or off");
  }
  return mode == "auto";
}

double initialisation_epoch(const std::vector<ImuIncrement>& imu, const std::vector<GnssFix>& gnss,
                            const KfGinsConfig& cfg, const AlignmentOptions& alignment) {
  size_t i = first_imu_index(imu, cfg);
  SessionOptions so = session_options_from(cfg, FilterOptions{}, &alignment);
  so.alignment.course_hypotheses = 1;  // the trial turns the heading, not the epoch
  NavFilter filter(so.filter);
  NavSession session(so, filter, nullptr);
  size_t g = 0;
  for (; i < imu.size() && !session.navigating(); ++i) {
    for (; g < gnss.size() && gnss[g].t_s <= imu[i].t_s + NavSession::kLookahead_s; ++g)
      session.add_gnss(gnss[g], gnss[g].t_s);
    session.add_imu(imu[i], 0, imu[i].t_s);
  }
  session.finish();
  if (!session.navigating()) throw InputError(cfg.gnss_path, 0, could_not_align(so));
  return session.started_at_s();
}

namespace {

// "vrw (accel white noise) was 0 on x y z: the standstill's 0.02 0.02 0.03 m/s/sqrt(h) taken" (and arw alike).
std::string unset_white_noise_note(const Vec3& arw0, const Vec3& vrw0, const FilterOptions& now) {
  std::string note;
  auto add = [&](const char* key, const char* what, const Vec3& before, const Vec3& after, double to_unit,
                 const char* unit) {
    std::string axes, values;
    for (int a = 0; a < 3; ++a) {
      if (before(a) != after(a)) {
        axes += std::string(axes.empty() ? "" : " ") + "xyz"[a];
        char v[32];
        std::snprintf(v, sizeof v, "%s%.3g", values.empty() ? "" : " ", after(a) * to_unit);
        values += v;
      }
    }
    if (axes.empty()) return;
    note += std::string(note.empty() ? "" : "; ") + key + " (" + what + ") was 0 on " + axes + ": the standstill's " +
            values + " " + unit + " taken";
  };
  add("imunoise.arw", "gyro white noise", arw0, now.arw_rad_per_sqrt_s, kRadToDeg * 60.0, "deg/sqrt(h)");
  add("imunoise.vrw", "accel white noise", vrw0, now.vrw_mps_per_sqrt_s, 60.0, "m/s/sqrt(h)");
  return note;
}

}  // namespace

RunSummary run_navigation(const std::vector<ImuIncrement>& imu, const std::vector<GnssFix>& gnss,
                          const KfGinsConfig& cfg, NavFilter& filter, const RunCallbacks& cb,
                          const AlignmentOptions* alignment, const std::vector<ObservationPtr>* others) {
  RunSummary sum;
  size_t i = first_imu_index(imu, cfg);
  std::optional<ImuNoiseScale> noise_floor;
  double standstill_f_scatter_mps2 = 0.0;
  if (filter.options().adapt_imu_noise && filter.options().installed_noise_floor) {
    const InstalledImuNoise noise = measure_installed_imu_noise(imu, gnss);
    if (noise.found) {
      const Vec3 arw0 = filter.options().arw_rad_per_sqrt_s, vrw0 = filter.options().vrw_mps_per_sqrt_s;
      if (filter.fill_unset_white_noise(noise.arw_rad_per_sqrt_s, noise.vrw_mps_per_sqrt_s))
        sum.white_noise_filled = unset_white_noise_note(arw0, vrw0, filter.options());
    }
    noise_floor = noise.psd_scale(filter.options().arw_rad_per_sqrt_s, filter.options().vrw_mps_per_sqrt_s);
    sum.imu_noise_standstill_s = noise.found ? noise.standstill_s : 0.0;
    if (noise.found) standstill_f_scatter_mps2 = noise.f_norm_scatter_mps2;
  }
  if (filter.options().imu_stamp_jitter_from_tags) {
    sum.imu_stamp_jitter = measure_imu_stamp_jitter(imu);
    if (sum.imu_stamp_jitter.found) filter.set_imu_stamp_jitter(sum.imu_stamp_jitter.sigma_s);
  }
  SessionOptions so = session_options_from(cfg, filter.options(), alignment);
  so.imu_noise_floor = noise_floor;
  so.standstill_f_scatter_mps2 = standstill_f_scatter_mps2;
  double last_epoch_s = NAN;  // the last solution epoch (a run re-aligning at its end has none after it)
  NavSession session(so, filter, [&](const NavFilter& f, int) {
    last_epoch_s = f.state().t_s;
    if (cb.on_innovation)
      for (const auto& r : filter.take_innovations()) cb.on_innovation(r);
    else if (filter.innovations().size() > 4096)
      filter.take_innovations();
    if (cb.on_epoch) cb.on_epoch(f);
  });

  // Each reading is handed over before the IMU passes its epoch (NavSession::kLookahead_s ahead), as a
  // receiver would deliver it: the filter applies it exactly there. Arrival time = data time.
  const std::vector<ObservationPtr> no_others;
  const std::vector<ObservationPtr>& other = others ? *others : no_others;
  size_t g = 0, o = 0;
  const double t1 = so.end_time_s;
  const size_t n_total = imu.size();
  const size_t progress_step = std::max<size_t>(1, n_total / 50);
  for (; i < imu.size() && imu[i].t_s <= t1; ++i) {
    const double t_feed = imu[i].t_s + NavSession::kLookahead_s;
    for (; g < gnss.size() && gnss[g].t_s <= t_feed; ++g) session.add_gnss(gnss[g], imu[i].t_s);
    for (; o < other.size() && other[o]->t_s <= t_feed; ++o) session.add_observation(other[o], imu[i].t_s);
    session.add_imu(imu[i], 0, imu[i].t_s);
    if (cb.on_progress && i % progress_step == 0) cb.on_progress(static_cast<double>(i) / n_total);
  }
  session.finish();
  // Never started: an error. (Started, then aligning again at the end after a failed heading: the run stands.)
  if (session.imu_samples_used() == 0) throw InputError(cfg.gnss_path, 0, could_not_align(so));
  sum.imu_samples = session.imu_samples_used();
  sum.gnss_fixes = session.gnss_fixes_used();
  sum.other_observations = session.other_readings_used();
  sum.initialisation = session.initialisation();
  sum.body_heading = session.body_heading();
  sum.gyro_bias_seed_rad_s = session.gyro_bias_seed_rad_s();
  sum.gyro_bias_seed_std_rad_s = session.gyro_bias_seed_std_rad_s();
  sum.imu_noise_floor = session.imu_noise_floor();
  sum.t_start_s = session.started_at_s();
  sum.t_end_s = std::isfinite(last_epoch_s) ? last_epoch_s : filter.state().t_s;
  sum.faults = filter.faults();
  sum.imu_noise_scale_end = filter.imu_noise_scale();
  sum.final_status = filter.status();
  return sum;
}

}  // namespace ldv::est
