#include "sim/truth_integrator.hpp"

#include <cmath>

#include "common/geo/earth_model.hpp"

namespace ldv::sim {
namespace {
// 3-point Gauss-Legendre on [0, 1]: nodes and weights.
constexpr double kGlNode[3] = {0.5 - 0.3872983346207417, 0.5, 0.5 + 0.3872983346207417};
constexpr double kGlWeight[3] = {5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0};

Vec3 hermite(const Vec3& p0, const Vec3& d0, const Vec3& p1, const Vec3& d1, double h, double s) {
  const double s2 = s * s, s3 = s2 * s;
  return (2 * s3 - 3 * s2 + 1) * p0 + (s3 - 2 * s2 + s) * h * d0 + (-2 * s3 + 3 * s2) * p1 + (s3 - s2) * h * d1;
}

TruthSample make_sample(double t_sow, const Kinematics& k, const Vec3& lla, const Sensed& s) {
  TruthSample out;
  out.t_s = t_sow;
  out.pos = {lla[0], wrap_pi(lla[1]), lla[2]};
  out.vel_n_mps = k.v_n_mps + Vec3::Zero();  // + 0 turns -0 into 0 for the text outputs
  out.rpy_rad = Vec3(k.rpy_rad.x(), k.rpy_rad.y(), wrap_pi(k.rpy_rad.z()));
  out.omega_ib_b_rad_s = s.omega_ib_b_rad_s;
  out.f_b_mps2 = s.f_b_mps2;
  return out;
}
}  // namespace

Vec3 lla_rate(const Vec3& lla, const Vec3& v_n) {
  const earth::Radii r = earth::radii(lla[0]);
  return {v_n.x() / (r.meridian_m + lla[2]), v_n.y() / ((r.prime_vertical_m + lla[2]) * std::cos(lla[0])), -v_n.z()};
}

Sensed sensed_at(const Kinematics& k, const Vec3& lla, const Vec3& dg_n) {
  const Vec3 w_ie_n = earth::omega_ie_n(lla[0]);
  const Vec3 w_en_n = earth::omega_en_n(lla[0], lla[2], k.v_n_mps);
  const Vec3 g_n = earth::gravity_n(lla[0], lla[2]) + dg_n;
  const Mat3 C_n_b = k.C_b_n.transpose();
  return {k.omega_nb_b_rad_s + C_n_b * (w_ie_n + w_en_n),
          C_n_b * (k.dv_n_dt_mps2 + (2.0 * w_ie_n + w_en_n).cross(k.v_n_mps) - g_n)};
}

TruthRun integrate_truth(const MotionProfile& m, const TruthOptions& opt, const std::function<void(double)>& progress) {
  TruthRun run;
  const size_t n = opt.intervals;
  const int M = opt.substeps;
  run.truth.reserve(n + 1);
  run.increments.resize(n);
  if (opt.with_squares) {
    run.omega_sq_integral.assign(n, Vec3::Zero());
    run.f_sq_integral.assign(n, Vec3::Zero());
  }
  auto anomaly = [&](size_t k) -> Vec3 {
    if (!opt.gravity_anomaly_n || opt.gravity_anomaly_n->empty()) return Vec3::Zero();
    return (*opt.gravity_anomaly_n)[std::min(k, opt.gravity_anomaly_n->size() - 1)];
  };

  Vec3 p0(m.start.pos.lat_rad, m.start.pos.lon_rad, m.start.pos.h_m);
  Kinematics K0 = kinematics_at(m, 0.0);
  run.truth.push_back(make_sample(opt.t0_sow_s, K0, p0, sensed_at(K0, p0, anomaly(0))));
  const size_t progress_every = std::max<size_t>(1, n / 100);

  for (size_t k = 0; k < n; ++k) {
    const Vec3 dg = anomaly(k);
    const double ta = static_cast<double>(k) * opt.dt_s;
    const double tb = static_cast<double>(k + 1) * opt.dt_s;
    Vec3 dtheta = Vec3::Zero(), dvel = Vec3::Zero(), w_sq = Vec3::Zero(), f_sq = Vec3::Zero();
    for (int j = 0; j < M; ++j) {
      const double s0 = ta + (tb - ta) * j / M;
      const double s1 = j + 1 == M ? tb : ta + (tb - ta) * (j + 1) / M;
      const double h = s1 - s0;
      const Kinematics Km = kinematics_at(m, s0 + 0.5 * h);
      const Kinematics K1 = kinematics_at(m, s1);
      // RK4 for the position; the velocity is known in closed form at every stage time.
      const Vec3 d0 = lla_rate(p0, K0.v_n_mps);
      const Vec3 k2 = lla_rate(p0 + 0.5 * h * d0, Km.v_n_mps);
      const Vec3 k3 = lla_rate(p0 + 0.5 * h * k2, Km.v_n_mps);
      const Vec3 k4 = lla_rate(p0 + h * k3, K1.v_n_mps);
      const Vec3 p1 = p0 + (h / 6.0) * (d0 + 2.0 * k2 + 2.0 * k3 + k4);
      const Vec3 d1 = lla_rate(p1, K1.v_n_mps);
      for (int q = 0; q < 3; ++q) {
        const double s = kGlNode[q];
        const Kinematics Kq = q == 1 ? Km : kinematics_at(m, s0 + s * h);
        const Sensed sq = sensed_at(Kq, hermite(p0, d0, p1, d1, h, s), dg);
        const double w = kGlWeight[q] * h;
        dtheta += w * sq.omega_ib_b_rad_s;
        dvel += w * sq.f_b_mps2;
        if (opt.with_squares) {
          w_sq += w * sq.omega_ib_b_rad_s.cwiseAbs2();
          f_sq += w * sq.f_b_mps2.cwiseAbs2();
        }
      }
      p0 = p1;
      K0 = K1;
    }
    ImuIncrement& inc = run.increments[k];
    inc.t_s = opt.t0_sow_s + tb;
    inc.dt_s = opt.dt_s;
    inc.dtheta_b_rad = dtheta;
    inc.dvel_b_mps = dvel;
    if (opt.with_squares) {
      run.omega_sq_integral[k] = w_sq;
      run.f_sq_integral[k] = f_sq;
    }
    run.truth.push_back(make_sample(opt.t0_sow_s + tb, K0, p0, sensed_at(K0, p0, dg)));
    if (progress && (k + 1) % progress_every == 0) progress(static_cast<double>(k + 1) / n);
  }
  return run;
}

}  // namespace ldv::sim
