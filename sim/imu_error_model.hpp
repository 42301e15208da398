#pragma once
// The IMU sensor model of docs/effects.md applied to exact increments (continuous-rate form
// integrated over each sample):
//   dtheta_meas = (I + diag(s_g) + N(m_g)) dtheta + k_g * int(w^2) + int(b_g) + diag(G) dvel + noise
//   dvel_meas   = (I + diag(s_a) + N(m_a)) dvel   + k_a * int(f^2) + int(b_a)                 + noise
// b(t) = constant + sum of Gauss-Markov + random walk K + ramp R t + sinusoid (held over a sample,
// ramp and sinusoid at the sample midpoint); noise = white N + the paper's quantisation Q: an additive
// white error e_k of std Q on the integrated quantity (angle / velocity), so each increment gets
// e_k - e_{k-1} (e_k uniform in +-Q sqrt(3), its own random stream; Allan variance exactly 3 Q^2 / tau^2).
// With `quantization_rounding` the running integral is rounded to the step Q sqrt(12) instead, as a
// sensor that outputs quantised accumulated angle / velocity does (white only when dithered by noise).
#include <vector>

#include "common/formats/nav_types.hpp"
#include "sim/random.hpp"

namespace ldv::sim {

struct GaussMarkovTerm {
  Vec3 sigma = Vec3::Zero();
  Vec3 tau_s = Vec3::Constant(3600.0);
};

struct TriadSensorModel {
  Vec3 bias = Vec3::Zero();           // constant [u]
  Vec3 scale = Vec3::Zero();          // [-]
  Vec3 misalignment_rad = Vec3::Zero();
  Vec3 nonlinear = Vec3::Zero();      // [1/u]
  std::vector<GaussMarkovTerm> gauss_markov;
  Vec3 rate_rw_K = Vec3::Zero();      // [u/sqrt(s)]
  Vec3 ramp_R = Vec3::Zero();         // [u/s]
  Vec3 sinusoid_amplitude = Vec3::Zero(), sinusoid_hz = Vec3::Zero();
  Vec3 white_N = Vec3::Zero();        // [u/sqrt(s)]
  Vec3 quantization_Q = Vec3::Zero(); // [u s]
  bool quantization_rounding = false; // false: the paper's Q (white error of the integral); true: ADC rounding
  bool any_nonlinear() const { return !nonlinear.isZero(); }
};

struct ImuSensorModel {
  TriadSensorModel gyro, accel;
  Vec3 g_sensitivity = Vec3::Zero();  // [rad/s per m/s^2], diagonal
  bool with_noise = true;             // false: no white, Gauss-Markov, random walk or quantisation noise
};

// The symmetric non-orthogonality matrix N(m) of docs/effects.md.
Mat3 non_orthogonality(const Vec3& m);

// Moving-bias state at one instant (for the truth_errors.txt history).
struct ImuBiasSample {
  double t_s = 0.0;
  Vec3 gyro_bias_rad_s = Vec3::Zero(), accel_bias_mps2 = Vec3::Zero();  // constant + moving parts
};

class ImuErrorSimulator {
 public:
  ImuErrorSimulator(const ImuSensorModel& model, uint64_t seed);
  // `t_mid_s`: run time at the middle of the sample; w_sq/f_sq: integrals of the squared true rates
  // (only read when a nonlinear scale is present).
  ImuIncrement apply(const ImuIncrement& truth, double t_mid_s, const Vec3& w_sq, const Vec3& f_sq);
  ImuBiasSample current_bias(double t_s) const;

 private:
  struct TriadState {
    std::vector<Vec3> gm;   // per Gauss-Markov term
    Vec3 rw = Vec3::Zero();
    Vec3 phase = Vec3::Zero();
    Vec3 cumulative = Vec3::Zero(), last_output = Vec3::Zero();  // rounding quantiser
    Vec3 q_error = Vec3::Zero();                                 // white quantisation error e_{k-1}
  };
  Vec3 apply_triad(const TriadSensorModel& m, TriadState& s, Rng& white, Rng& moving, Rng& quant, const Vec3& exact, double dt,
                   double t_mid_s, const Vec3& sq, const Mat3& M);
  Vec3 moving_bias(const TriadSensorModel& m, const TriadState& s, double t_s) const;

  ImuSensorModel model_;
  Mat3 M_gyro_, M_accel_;
  TriadState gyro_, accel_;
  Rng gyro_white_, accel_white_, gyro_moving_, accel_moving_, gyro_quant_, accel_quant_;
};

}  // namespace ldv::sim
