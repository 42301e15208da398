#include "sim/motion_profile.hpp"

#include <algorithm>
#include <stdexcept>

namespace ldv::sim {
namespace {
// Quintic smootherstep S(u), its derivative and its integral from 0 to u.
double S(double u) { return u * u * u * (10.0 + u * (-15.0 + 6.0 * u)); }
double dS(double u) { return 30.0 * u * u * (1.0 + u * (-2.0 + u)); }
double intS(double u) { return u * u * u * u * (2.5 + u * (-3.0 + u)); }
}  // namespace

void Channel::ramp_to(double t0_s, double length_s, double to) {
  if (length_s < 0.0) throw std::invalid_argument("Channel::ramp_to: negative ramp length");
  double integral = 0.0;
  const double from = final_value();
  if (ramps_.empty()) {
    if (t0_s < 0.0) throw std::invalid_argument("Channel::ramp_to: ramp before t = 0");
    integral = initial_ * t0_s;
  } else {
    const Ramp& p = ramps_.back();
    const double p_end = p.t0_s + p.length_s;
    if (t0_s < p_end - 1e-9) throw std::invalid_argument("Channel::ramp_to: overlapping ramps");
    integral = integral_at_ramp_start_.back() + p.length_s * 0.5 * (p.from + p.to) + p.to * (t0_s - p_end);
  }
  ramps_.push_back({t0_s, length_s, from, to});
  integral_at_ramp_start_.push_back(integral);
}

Channel::Sample Channel::at(double t) const {
  // Last ramp starting at or before t.
  auto it = std::upper_bound(ramps_.begin(), ramps_.end(), t, [](double x, const Ramp& r) { return x < r.t0_s; });
  if (it == ramps_.begin()) return {initial_, 0.0, initial_ * t};
  const size_t i = static_cast<size_t>(it - ramps_.begin()) - 1;
  const Ramp& r = ramps_[i];
  const double I0 = integral_at_ramp_start_[i];
  const double delta = r.to - r.from;
  const double end = r.t0_s + r.length_s;
  if (t < end) {
    const double u = (t - r.t0_s) / r.length_s;
    return {r.from + delta * S(u), delta * dS(u) / r.length_s, I0 + r.length_s * (r.from * u + delta * intS(u))};
  }
  return {r.to, 0.0, I0 + r.length_s * 0.5 * (r.from + r.to) + r.to * (t - end)};
}

Kinematics kinematics_at(const MotionProfile& m, double t) {
  const Channel::Sample a = m.accel_mps2.at(t), yr = m.yaw_rate_rad_s.at(t);
  const Channel::Sample p = m.pitch_rad.at(t), r = m.roll_rad.at(t);
  Kinematics k;
  k.speed_mps = m.start.speed_mps + a.integral;
  k.accel_mps2 = a.value;
  double roll = r.value, roll_rate = r.rate;
  if (!m.coordinated.ramps().empty() && m.coordinated.at(t).value != 0.0) {
    const double u = k.speed_mps * yr.value / kStandardGravity_mps2;
    const double du = (k.accel_mps2 * yr.value + k.speed_mps * yr.rate) / kStandardGravity_mps2;
    roll += std::atan(u);
    roll_rate += du / (1.0 + u * u);
  }
  k.vehicle_rpy_rad = Vec3(roll, p.value, m.start.yaw_rad + yr.integral);
  k.vehicle_rpy_rate_rad_s = Vec3(roll_rate, p.rate, yr.value);

  const double sr = std::sin(roll), cr = std::cos(roll);
  const double sp = std::sin(p.value), cp = std::cos(p.value);
  const double sy = std::sin(k.vehicle_rpy_rad.z()), cy = std::cos(k.vehicle_rpy_rad.z());
  k.C_v_n << cp * cy, -cr * sy + sr * sp * cy, sr * sy + cr * sp * cy,  //
      cp * sy, cr * cy + sr * sp * sy, -sr * cy + cr * sp * sy,         //
      -sp, sr * cp, cr * cp;
  const double dp = p.rate, dy = yr.value, dr = roll_rate;
  // ZYX Euler rates to the vehicle rate relative to NED, in vehicle axes.
  k.omega_nv_v_rad_s = Vec3(dr - dy * sp, dp * cr + dy * sr * cp, -dp * sr + dy * cr * cp);
  if (m.slip_rad_per_mps2 == 0.0) {
    // Direction of travel (vehicle x in NED) and its time derivative.
    const Vec3 u(cp * cy, cp * sy, -sp);
    const Vec3 du(-sp * dp * cy - cp * sy * dy, -sp * dp * sy + cp * cy * dy, -cp * dp);
    k.v_n_mps = k.speed_mps * u;
    k.dv_n_dt_mps2 = k.accel_mps2 * u + k.speed_mps * du;
  } else {
    // Velocity along u_v = (cos b, sin b, 0) in vehicle axes, b = -k speed yaw_rate;
    // d(C_v_n u_v)/dt = C_v_n (w_nv_v x u_v + du_v/dt).
    k.slip_rad = -m.slip_rad_per_mps2 * k.speed_mps * yr.value;
    const double db = -m.slip_rad_per_mps2 * (k.accel_mps2 * yr.value + k.speed_mps * yr.rate);
    const Vec3 u_v(std::cos(k.slip_rad), std::sin(k.slip_rad), 0.0);
    const Vec3 du_v = k.omega_nv_v_rad_s.cross(u_v) + db * Vec3(-u_v.y(), u_v.x(), 0.0);
    k.v_n_mps = k.speed_mps * (k.C_v_n * u_v);
    k.dv_n_dt_mps2 = k.C_v_n * (k.accel_mps2 * u_v + k.speed_mps * du_v);
  }
  if (!m.mounted) {
    k.rpy_rad = k.vehicle_rpy_rad;
    k.C_b_n = k.C_v_n;
    k.omega_nb_b_rad_s = k.omega_nv_v_rad_s;
  } else {
    k.C_b_n = k.C_v_n * m.C_b_v;
    k.omega_nb_b_rad_s = m.C_b_v.transpose() * k.omega_nv_v_rad_s;
    k.rpy_rad = euler_from_C_b_n(k.C_b_n);
  }
  return k;
}

}  // namespace ldv::sim
