#include "sim/imu_error_model.hpp"

#include <cmath>

namespace ldv::sim {

Mat3 non_orthogonality(const Vec3& m) {
  Mat3 N;
  N << 0.0, m.z(), m.y(),  //
      m.z(), 0.0, m.x(),   //
      m.y(), m.x(), 0.0;
  return N;
}

ImuErrorSimulator::ImuErrorSimulator(const ImuSensorModel& model, uint64_t seed)
    : model_(model),
      gyro_white_(seed, "gyro_white"),
      accel_white_(seed, "accel_white"),
      gyro_moving_(seed, "gyro_moving"),
      accel_moving_(seed, "accel_moving"),
      gyro_quant_(seed, "gyro_quantization"),
      accel_quant_(seed, "accel_quantization") {
  M_gyro_ = Mat3::Identity() + Mat3(model.gyro.scale.asDiagonal()) + non_orthogonality(model.gyro.misalignment_rad);
  M_accel_ = Mat3::Identity() + Mat3(model.accel.scale.asDiagonal()) + non_orthogonality(model.accel.misalignment_rad);
  Rng init(seed, "imu_initial_state");
  auto init_triad = [&](const TriadSensorModel& m, TriadState& s) {
    for (const auto& gm : m.gauss_markov) {
      // Start from the stationary distribution: no transient in the Allan deviation.
      Vec3 x;
      for (int i = 0; i < 3; ++i) x[i] = model.with_noise ? gm.sigma[i] * init.normal() : 0.0;
      s.gm.push_back(x);
    }
    for (int i = 0; i < 3; ++i) {
      s.phase[i] = 2.0 * kPi * init.uniform();
      // A random position of the running integral within one quantisation step.
      const double step = m.quantization_Q[i] * std::sqrt(12.0);
      s.cumulative[i] = step * init.uniform();
      s.last_output[i] = step > 0 ? step * std::round(s.cumulative[i] / step) : 0.0;
    }
  };
  init_triad(model.gyro, gyro_);
  init_triad(model.accel, accel_);
  // The white quantisation error of the integral before the first sample (stationary from the start).
  auto init_q = [&](const TriadSensorModel& m, TriadState& s, Rng& quant) {
    for (int i = 0; i < 3; ++i)
      if (model.with_noise && !m.quantization_rounding && m.quantization_Q[i] > 0)
        s.q_error[i] = m.quantization_Q[i] * std::sqrt(12.0) * (quant.uniform() - 0.5);
  };
  init_q(model.gyro, gyro_, gyro_quant_);
  init_q(model.accel, accel_, accel_quant_);
}

Vec3 ImuErrorSimulator::moving_bias(const TriadSensorModel& m, const TriadState& s, double t) const {
  Vec3 b = m.bias + s.rw + m.ramp_R * t;
  for (const Vec3& x : s.gm) b += x;
  for (int i = 0; i < 3; ++i)
    if (m.sinusoid_amplitude[i] != 0.0)
      b[i] += m.sinusoid_amplitude[i] * std::sin(2.0 * kPi * m.sinusoid_hz[i] * t + s.phase[i]);
  return b;
}

Vec3 ImuErrorSimulator::apply_triad(const TriadSensorModel& m, TriadState& s, Rng& white, Rng& moving,
                                    Rng& quant, const Vec3& exact, double dt, double t_mid, const Vec3& sq, const Mat3& M) {
  Vec3 out = M * exact + moving_bias(m, s, t_mid) * dt;
  if (m.any_nonlinear()) out += m.nonlinear.cwiseProduct(sq);
  if (!model_.with_noise) return out;
  const double sqrt_dt = std::sqrt(dt);
  for (int i = 0; i < 3; ++i) {
    if (m.white_N[i] > 0) out[i] += m.white_N[i] * sqrt_dt * white.normal();
  }
  // Advance the moving-bias states to the next sample.
  for (size_t j = 0; j < m.gauss_markov.size(); ++j) {
    const auto& gm = m.gauss_markov[j];
    for (int i = 0; i < 3; ++i) {
      if (gm.sigma[i] <= 0) continue;
      const double phi = std::exp(-dt / gm.tau_s[i]);
      s.gm[j][i] = phi * s.gm[j][i] + gm.sigma[i] * std::sqrt(1.0 - phi * phi) * moving.normal();
    }
  }
  for (int i = 0; i < 3; ++i)
    if (m.rate_rw_K[i] > 0) s.rw[i] += m.rate_rw_K[i] * sqrt_dt * moving.normal();
  // The paper's Q: a white error e_k of std Q on the integral (uniform over one step Q sqrt(12), as an ideally
  // dithered quantiser's), so the increment carries e_k - e_{k-1}.
  if (!m.quantization_rounding) {
    for (int i = 0; i < 3; ++i) {
      const double step = m.quantization_Q[i] * std::sqrt(12.0);
      if (step <= 0) continue;
      const double e = step * (quant.uniform() - 0.5);
      out[i] += e - s.q_error[i];
      s.q_error[i] = e;
    }
    return out;
  }
  // ADC rounding of the running integral.
  for (int i = 0; i < 3; ++i) {
    const double step = m.quantization_Q[i] * std::sqrt(12.0);
    if (step <= 0) continue;
    s.cumulative[i] += out[i];
    const double q = step * std::round(s.cumulative[i] / step);
    out[i] = q - s.last_output[i];
    s.last_output[i] = q;
  }
  return out;
}

ImuIncrement ImuErrorSimulator::apply(const ImuIncrement& truth, double t_mid, const Vec3& w_sq, const Vec3& f_sq) {
  ImuIncrement out = truth;
  out.dtheta_b_rad = apply_triad(model_.gyro, gyro_, gyro_white_, gyro_moving_, gyro_quant_, truth.dtheta_b_rad, truth.dt_s, t_mid,
                                 w_sq, M_gyro_);
  if (!model_.g_sensitivity.isZero()) out.dtheta_b_rad += model_.g_sensitivity.cwiseProduct(truth.dvel_b_mps);
  out.dvel_b_mps = apply_triad(model_.accel, accel_, accel_white_, accel_moving_, accel_quant_, truth.dvel_b_mps, truth.dt_s, t_mid,
                               f_sq, M_accel_);
  return out;
}

ImuBiasSample ImuErrorSimulator::current_bias(double t_s) const {
  return {t_s, moving_bias(model_.gyro, gyro_, t_s), moving_bias(model_.accel, accel_, t_s)};
}

}  // namespace ldv::sim
