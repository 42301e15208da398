#include "common/formats/imu_sample_checks.hpp"

#include <cmath>

#include "common/io/number_text.hpp"

namespace ldv {

std::optional<std::string> imu_increment_implausibility(const Vec3& dtheta_b_rad, const Vec3& dvel_b_mps, double dt_s) {
  if (!std::isfinite(dt_s) || !(dt_s > 0.0) || !(dt_s < kMaxImuInterval_s))
    return "interval " + six_significant(dt_s) + " s not in (0, " + six_significant(kMaxImuInterval_s) + ")";
  return imu_rate_implausibility(dtheta_b_rad, dvel_b_mps, dt_s);
}

std::optional<std::string> imu_rate_implausibility(const Vec3& dtheta_b_rad, const Vec3& dvel_b_mps, double dt_s) {
  if (!std::isfinite(dt_s) || !(dt_s > 0.0)) return "interval " + six_significant(dt_s) + " s not positive";
  if (!dtheta_b_rad.allFinite() || !dvel_b_mps.allFinite()) return "increment not finite";
  // Per axis, as an IMU's range is stated.
  const double rate = dtheta_b_rad.cwiseAbs().maxCoeff() / dt_s;
  if (rate > kMaxPlausibleAngularRate_rad_s)
    return "angular rate " + six_significant(rate) + " rad/s beyond any IMU (" +
           six_significant(kMaxPlausibleAngularRate_rad_s) + " rad/s)";
  const double force = dvel_b_mps.cwiseAbs().maxCoeff() / dt_s;
  if (force > kMaxPlausibleSpecificForce_mps2)
    return "specific force " + six_significant(force) + " m/s^2 beyond any IMU (" +
           six_significant(kMaxPlausibleSpecificForce_mps2) + " m/s^2)";
  return std::nullopt;
}

}  // namespace ldv
