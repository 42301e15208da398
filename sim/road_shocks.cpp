#include "sim/road_shocks.hpp"

#include <cmath>

#include "sim/random.hpp"

namespace ldv::sim {
namespace {
// One bump's angle and heave at time s after its start (zero outside [0, T]).
void add_bump(const ShockEvent& e, double s, Vec3& angle, Vec3& heave) {
  if (s <= 0.0 || s >= e.duration_s) return;
  const double w = e.omega_rad_s();
  const double shape = std::exp(-s / e.tau_s()) * std::sin(w * s) / w;
  angle += Vec3(e.roll_rate_peak_rad_s, e.pitch_rate_peak_rad_s, 0.0) * shape;
  heave.z() += e.vertical_accel_peak_mps2 * shape;
}
}  // namespace

double ShockEvent::omega_rad_s() const { return 3.0 * kPi / duration_s; }
double ShockEvent::tau_s() const { return duration_s / 3.0; }

std::vector<ShockEvent> draw_shocks(const std::vector<TruthSample>& truth, double dt, double per_km, uint64_t seed) {
  std::vector<ShockEvent> out;
  if (per_km <= 0.0 || truth.size() < 2) return out;
  Rng rng(seed, "shocks");
  const double per_m = per_km * 1e-3;
  auto gap_m = [&] { return -std::log(1.0 - rng.uniform()) / per_m; };
  double next_m = gap_m(), d = 0.0;
  for (size_t k = 1; k < truth.size(); ++k) {
    const double step = 0.5 * (truth[k - 1].vel_n_mps.norm() + truth[k].vel_n_mps.norm()) * dt;
    while (step > 0.0 && d + step >= next_m) {
      ShockEvent e;
      e.t_start_s = (static_cast<double>(k - 1) + (next_m - d) / step) * dt;
      e.duration_s = 0.1 + 0.2 * rng.uniform();
      const double sign_p = rng.uniform() < 0.5 ? -1.0 : 1.0, sign_a = rng.uniform() < 0.5 ? -1.0 : 1.0;
      e.pitch_rate_peak_rad_s = sign_p * (10.0 + 30.0 * rng.uniform()) * kDegToRad;
      e.roll_rate_peak_rad_s = (rng.uniform() - 0.5) * e.pitch_rate_peak_rad_s;
      e.vertical_accel_peak_mps2 = sign_a * (1.0 + 3.0 * rng.uniform());
      out.push_back(e);
      next_m += gap_m();
    }
    d += step;
  }
  return out;
}

// Angle [rad] and heave velocity [m/s] of the bumps under way at run time t, vehicle axes.
void RoadShocks::state(double t, Vec3& angle, Vec3& heave) const {
  angle.setZero();
  heave.setZero();
  for (size_t i = first_; i < events_.size() && events_[i].t_start_s < t; ++i)
    add_bump(events_[i], t - events_[i].t_start_s, angle, heave);
}

void RoadShocks::add(ImuIncrement& inc, double ta, double tb) {
  while (first_ < events_.size() && events_[first_].t_start_s + events_[first_].duration_s <= ta) ++first_;
  if (first_ == events_.size() || events_[first_].t_start_s >= tb) return;
  Vec3 angle_a, heave_a, angle_b, heave_b, angle_m, heave_m;
  state(ta, angle_a, heave_a);
  state(tb, angle_b, heave_b);
  state(0.5 * (ta + tb), angle_m, heave_m);
  // The body turned by the small angle senses the true rate and specific force rotated by it.
  const Vec3 angle_m_b = C_v_b_ * angle_m;
  const Vec3 coupling_theta = -angle_m_b.cross(inc.dtheta_b_rad), coupling_vel = -angle_m_b.cross(inc.dvel_b_mps);
  inc.dtheta_b_rad += C_v_b_ * (angle_b - angle_a) + coupling_theta;
  inc.dvel_b_mps += C_v_b_ * (heave_b - heave_a) + coupling_vel;
}

}  // namespace ldv::sim
