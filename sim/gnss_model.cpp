#include "sim/gnss_model.hpp"

#include <algorithm>
#include <cmath>

#include "common/geo/earth_model.hpp"
#include "common/io/input_error.hpp"
#include "sim/random.hpp"
#include "sim/truth_integrator.hpp"

namespace ldv::sim {

GnssErrorLevel gnss_error_level(const std::string& mode) {
  GnssErrorLevel l;
  if (mode == "fixed") {  // RTK fixed: ~1-2 cm horizontal, 2-3 cm vertical
    l.quality = GnssQuality::kFixed;
    l.white_std_ned_m = Vec3(0.008, 0.008, 0.015);
    l.colored_std_ned_m = Vec3(0.008, 0.008, 0.015);
    l.colored_tau_s = 60.0;
    l.vel_std_n_mps = Vec3(0.02, 0.02, 0.04);
    l.num_sats = 20;
    l.ratio = 15.0;
    l.age_s = 1.0;
  } else if (mode == "float") {  // RTK float: 0.2-0.5 m, mostly slowly varying
    l.quality = GnssQuality::kFloat;
    l.white_std_ned_m = Vec3(0.05, 0.05, 0.10);
    l.colored_std_ned_m = Vec3(0.25, 0.25, 0.40);
    l.colored_tau_s = 120.0;
    l.vel_std_n_mps = Vec3(0.05, 0.05, 0.08);
    l.num_sats = 16;
    l.ratio = 1.8;
    l.age_s = 1.0;
  } else if (mode == "single") {  // single point: 1-3 m
    l.quality = GnssQuality::kSingle;
    l.white_std_ned_m = Vec3(0.3, 0.3, 0.6);
    l.colored_std_ned_m = Vec3(1.2, 1.2, 2.5);
    l.colored_tau_s = 300.0;
    l.vel_std_n_mps = Vec3(0.1, 0.1, 0.15);
    l.num_sats = 9;
    l.ratio = 0.0;
    l.age_s = 0.0;
  } else {
    throw InputError("--gnss-mode", 0, "unknown GNSS solution type '" + mode + "': expected fixed, float or single");
  }
  return l;
}

AntennaTruth antenna_truth_at(const MotionProfile& m, const std::vector<TruthSample>& truth, double dt, double t,
                              const Vec3& lever_b) {
  const double k_real = t / dt;
  size_t k = static_cast<size_t>(std::max(0.0, std::floor(k_real)));
  if (k + 1 >= truth.size()) k = truth.size() - 2;
  const TruthSample& a = truth[k];
  const TruthSample& b = truth[k + 1];
  // Unwrapped longitude of b relative to a, then a cubic Hermite interpolant in (lat, lon, h).
  const Vec3 pa(a.pos.lat_rad, a.pos.lon_rad, a.pos.h_m);
  const Vec3 pb(b.pos.lat_rad, a.pos.lon_rad + wrap_pi(b.pos.lon_rad - a.pos.lon_rad), b.pos.h_m);
  const Vec3 da = lla_rate(pa, a.vel_n_mps), db = lla_rate(pb, b.vel_n_mps);
  const double s = (t - static_cast<double>(k) * dt) / dt, s2 = s * s, s3 = s2 * s;
  const Vec3 p = (2 * s3 - 3 * s2 + 1) * pa + (s3 - 2 * s2 + s) * dt * da + (-2 * s3 + 3 * s2) * pb + (s3 - s2) * dt * db;
  const Geodetic imu{p[0], wrap_pi(p[1]), p[2]};

  const Kinematics kin = kinematics_at(m, t);
  const Vec3 w_en_n = earth::omega_en_n(imu.lat_rad, imu.h_m, kin.v_n_mps);
  // Rate of the body relative to the Earth, in body axes: moves the antenna around the IMU.
  const Vec3 w_eb_b = kin.omega_nb_b_rad_s + kin.C_b_n.transpose() * w_en_n;
  AntennaTruth out;
  out.pos = earth::offset_ned(imu, kin.C_b_n * lever_b);
  out.vel_n_mps = kin.v_n_mps + kin.C_b_n * w_eb_b.cross(lever_b);
  return out;
}

GnssRun simulate_gnss(const MotionProfile& m, const std::vector<TruthSample>& truth, double dt,
                      const GnssErrorLevel& level, const GnssSchedule& sch, uint64_t seed) {
  GnssRun run;
  Rng white(seed, "gnss_white"), colored(seed, "gnss_colored"), latency(seed, "gnss_latency");
  Rng outliers(seed, "gnss_outliers");
  const double t0_sow = truth.front().t_s;
  const double t_end = truth.back().t_s - t0_sow;
  const double period = 1.0 / sch.rate_hz;
  // Epochs on the GPS-time grid of the rate (whole seconds for 1 Hz).
  const long first = static_cast<long>(std::ceil(t0_sow * sch.rate_hz - 1e-9));
  const long last = static_cast<long>(std::floor((t0_sow + t_end) * sch.rate_hz + 1e-9));
  Vec3 gm = Vec3::Zero();
  for (int i = 0; i < 3; ++i) gm[i] = sch.with_noise ? level.colored_std_ned_m[i] * colored.normal() : 0.0;
  const double phi = std::exp(-period / level.colored_tau_s);
  // The reported std is the noise actually simulated (1 mm when the noise is off: the text format's
  // resolution is ~1 um, and a zero std would be rejected by readers).
  const Vec3 pos_std = sch.with_noise
                           ? Vec3((level.white_std_ned_m.cwiseAbs2() + level.colored_std_ned_m.cwiseAbs2()).cwiseSqrt())
                           : Vec3::Constant(1e-3);
  const Vec3 vel_std = sch.with_noise ? level.vel_std_n_mps : Vec3::Constant(1e-3);

  for (long j = first; j <= last; ++j) {
    if (j > first)
      for (int i = 0; i < 3; ++i)
        gm[i] = phi * gm[i] + (sch.with_noise ? level.colored_std_ned_m[i] * std::sqrt(1 - phi * phi) * colored.normal() : 0.0);
    Vec3 w_pos = Vec3::Zero(), w_vel = Vec3::Zero();
    if (sch.with_noise)
      for (int i = 0; i < 3; ++i) {
        w_pos[i] = level.white_std_ned_m[i] * white.normal();
        w_vel[i] = level.vel_std_n_mps[i] * white.normal();
      }
    const double lat_s = sch.with_noise ? sch.latency_mean_s + sch.latency_jitter_s * (2.0 * latency.uniform() - 1.0)
                                        : sch.latency_mean_s;
    // Drawn every epoch (outages too), so the jumps fall on the same epochs whatever else changes.
    Vec3 jump = Vec3::Zero();
    if (sch.outlier_rate > 0.0) {
      const double u = outliers.uniform(), size_m = 1.0 + 2.0 * outliers.uniform();
      Vec3 dir(outliers.normal(), outliers.normal(), outliers.normal());
      if (u < sch.outlier_rate && dir.norm() > 0.0) jump = size_m * dir.normalized();
    }
    const double t_label_sow = static_cast<double>(j) / sch.rate_hz;
    const double t_label = t_label_sow - t0_sow;
    bool in_outage = false;
    for (const auto& o : sch.outages) in_outage |= t_label >= o.start_s && t_label < o.start_s + o.length_s;
    const double t_meas = t_label;
    if (in_outage || t_meas < 0.0 || t_meas > t_end) continue;

    const AntennaTruth ant = antenna_truth_at(m, truth, dt, t_meas, sch.lever_arm_b_m);
    GnssFix f;
    f.t_s = t_label_sow;
    f.pos = earth::offset_ned(ant.pos, gm + w_pos + jump);
    if (!jump.isZero()) run.outliers.push_back({t_label_sow, jump});
    f.pos_std_ned_m = pos_std;
    f.has_velocity = sch.with_velocity;
    const Vec3 vel_n =
        sch.velocity_lag_s > 0.0
            ? antenna_truth_at(m, truth, dt, std::clamp(t_meas - sch.velocity_lag_s, 0.0, t_end), sch.lever_arm_b_m)
                  .vel_n_mps
            : ant.vel_n_mps;
    f.vel_n_mps = vel_n + sch.velocity_noise_factor * w_vel;
    f.vel_std_n_mps = vel_std;
    f.quality = level.quality;
    f.num_sats = level.num_sats;
    f.age_s = level.age_s;
    f.ratio = level.ratio;
    run.fixes.push_back(f);
    run.latency_s.push_back(lat_s);
  }
  return run;
}

}  // namespace ldv::sim
