#pragma once
// Road bumps: a Poisson process in distance travelled (rate per km while moving). Each bump is a short
// damped oscillation of the IMU body about the smooth vehicle trajectory, in vehicle axes:
//   angle(s) = (roll_peak, pitch_peak, 0) / omega * e^{-s/tau} sin(omega s)      [rad]
//   heave(s) = (0, 0, accel_peak) / omega * e^{-s/tau} sin(omega s)                [m/s, vertical velocity]
// for 0 <= s <= T (omega = 3 pi / T: 1.5 cycles, tau = T / 3), zero outside; so the rates start at
// their peaks and angle and heave velocity are exactly zero again after T (the car returns to its pose).
// The IMU senses the rotated body: dtheta += d(angle) - angle x dtheta_true, dvel += d(heave) -
// angle x dvel_true (first order), so a strapdown integration returns to the smooth truth after the
// bump. The truth (truth.nav) is the smooth trajectory: it omits the < 2 deg, <= 0.3 s excursion.
#include <cstdint>
#include <vector>

#include "common/formats/nav_types.hpp"
#include "sim/truth_sample.hpp"

namespace ldv::sim {

struct ShockEvent {
  double t_start_s = 0.0;  // run time
  double duration_s = 0.0;
  double roll_rate_peak_rad_s = 0.0, pitch_rate_peak_rad_s = 0.0;  // vehicle x, y
  double vertical_accel_peak_mps2 = 0.0;                           // vehicle z (down +)
  double omega_rad_s() const;
  double tau_s() const;
};

// Bump times from the distance travelled along the truth (samples every dt from run time 0), sizes:
// duration U[0.1, 0.3] s, pitch rate +-U[10, 40] deg/s, roll rate U[-0.5, 0.5] x pitch rate, vertical
// accel +-U[1, 4] m/s^2 (stream "shocks").
std::vector<ShockEvent> draw_shocks(const std::vector<TruthSample>& truth, double dt_s, double per_km, uint64_t seed);

// Adds the bumps to successive increments (call in order of k).
class RoadShocks {
 public:
  RoadShocks(const std::vector<ShockEvent>& events, const Mat3& C_b_v) : events_(events), C_v_b_(C_b_v.transpose()) {}
  // `inc`: the exact increment over (ta, tb] (run time), modified in place.
  void add(ImuIncrement& inc, double ta_s, double tb_s);

 private:
  void state(double t, Vec3& angle, Vec3& heave) const;
  const std::vector<ShockEvent>& events_;
  Mat3 C_v_b_;
  size_t first_ = 0;  // first event not yet over
};

}  // namespace ldv::sim
