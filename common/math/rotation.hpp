#pragma once
// Rotation helpers. Conventions used everywhere in ldvnav:
//  - C_b_n maps body (front-right-down) vectors into the local-level NED frame: v_n = C_b_n * v_b.
//  - Euler angles are ZYX: C_b_n = Rz(yaw) * Ry(pitch) * Rx(roll); stored as (roll, pitch, yaw) [rad].
//  - Rotation vectors are right-handed; quat_from_rotvec(phi) rotates by |phi| about phi/|phi|.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

namespace ldv {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;

constexpr double kPi = 3.14159265358979323846;
constexpr double kHalfPi = kPi / 2.0;
constexpr double kDegToRad = kPi / 180.0;
constexpr double kRadToDeg = 180.0 / kPi;

inline Mat3 skew(const Vec3& v) {
  Mat3 m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

inline Mat3 C_b_n_from_euler(const Vec3& rpy_rad) {
  const double sr = std::sin(rpy_rad.x()), cr = std::cos(rpy_rad.x());
  const double sp = std::sin(rpy_rad.y()), cp = std::cos(rpy_rad.y());
  const double sy = std::sin(rpy_rad.z()), cy = std::cos(rpy_rad.z());
  Mat3 C;
  C << cp * cy, -cr * sy + sr * sp * cy, sr * sy + cr * sp * cy,  //
      cp * sy, cr * cy + sr * sp * sy, -sr * cy + cr * sp * sy,  //
      -sp, sr * cp, cr * cp;
  return C;
}

// Inverse of C_b_n_from_euler; yaw in (-pi, pi]. Near pitch = +-90 deg roll and yaw share one degree of
// freedom; we keep the formula's branch (roll from the last row) as KF-GINS does.
inline Vec3 euler_from_C_b_n(const Mat3& C) {
  const double pitch = std::atan2(-C(2, 0), std::sqrt(C(2, 1) * C(2, 1) + C(2, 2) * C(2, 2)));
  const double roll = std::atan2(C(2, 1), C(2, 2));
  const double yaw = std::atan2(C(1, 0), C(0, 0));
  return {roll, pitch, yaw};
}

inline Quat quat_from_rotvec(const Vec3& phi) {
  const double angle = phi.norm();
  if (angle < 1e-8) {
    // Second-order series keeps the quaternion unit to machine precision for tiny angles.
    const Vec3 half = 0.5 * phi;
    Quat q(1.0 - half.squaredNorm() / 2.0, half.x(), half.y(), half.z());
    return q.normalized();
  }
  const double s = std::sin(0.5 * angle) / angle;
  return Quat(std::cos(0.5 * angle), s * phi.x(), s * phi.y(), s * phi.z());
}

inline Vec3 rotvec_from_quat(Quat q) {
  if (q.w() < 0) q.coeffs() = -q.coeffs();
  const Vec3 v = q.vec();
  const double s = v.norm();
  if (s < 1e-12) return 2.0 * v;
  const double angle = 2.0 * std::atan2(s, q.w());
  return v * (angle / s);
}

inline Quat quat_from_euler(const Vec3& rpy_rad) { return Quat(C_b_n_from_euler(rpy_rad)).normalized(); }

// Wraps an angle into (-pi, pi].
inline double wrap_pi(double a) {
  a = std::fmod(a + kPi, 2.0 * kPi);
  if (a <= 0) a += 2.0 * kPi;
  return a - kPi;
}

}  // namespace ldv
