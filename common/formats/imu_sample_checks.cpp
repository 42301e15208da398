#include "common/formats/imu_sample_checks.hpp"

#include <cmath>
#include <cstdio>

namespace ldv {
namespace {
std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}
}  // namespace

std::optional<std::string> imu_increment_implausibility(const Vec3& dtheta_b_rad, const Vec3& dvel_b_mps, double dt_s) {
  if (!std::isfinite(dt_s) || !(dt_s > 0.0) || !(dt_s < kMaxImuInterval_s))
    return "interval " + num(dt_s) + " s not in (0, " + num(kMaxImuInterval_s) + ")";
  if (!dtheta_b_rad.allFinite() || !dvel_b_mps.allFinite()) return "increment not finite";
  // Per axis, as an IMU's range is stated.
  const double rate = dtheta_b_rad.cwiseAbs().maxCoeff() / dt_s;
  if (rate > kMaxPlausibleAngularRate_rad_s)
    return "angular rate " + num(rate) + " rad/s beyond any IMU (" + num(kMaxPlausibleAngularRate_rad_s) + " rad/s)";
  const double force = dvel_b_mps.cwiseAbs().maxCoeff() / dt_s;
  if (force > kMaxPlausibleSpecificForce_mps2)
    return "specific force " + num(force) + " m/s^2 beyond any IMU (" + num(kMaxPlausibleSpecificForce_mps2) +
           " m/s^2)";
  return std::nullopt;
}

}  // namespace ldv
