#include "common/formats/gnss_solution_checks.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <numbers>

#include "common/io/number_text.hpp"

namespace ldv::gnss {

std::optional<std::string> implausibility(const GpsTime& t) {
  if (t.week < kMinPlausibleGpsWeek || t.week > kMaxPlausibleGpsWeek)
    return "GPS week " + std::to_string(t.week) + " not in [" + std::to_string(kMinPlausibleGpsWeek) + ", " +
           std::to_string(kMaxPlausibleGpsWeek) + "]";
  if (!std::isfinite(t.sow_s) || t.sow_s < 0.0 || t.sow_s >= kSecondsPerWeek)
    return "time of week " + six_significant(t.sow_s) + " s not in [0, 604800)";
  return std::nullopt;
}

namespace {
// Everything of a solution but its time: the place, the covariance the update will use, the std, the velocity.
std::optional<std::string> fix_implausibility(const GnssFix& f, const Mat3& pos_cov_ned_m2) {
  constexpr double kPi = std::numbers::pi;
  if (!std::isfinite(f.pos.lat_rad) || std::abs(f.pos.lat_rad) > kPi / 2)
    return "latitude " + six_significant(f.pos.lat_rad * 180.0 / kPi) + " deg not in [-90, 90]";
  if (!std::isfinite(f.pos.lon_rad) || std::abs(f.pos.lon_rad) > 2 * kPi)
    return "longitude " + six_significant(f.pos.lon_rad * 180.0 / kPi) + " deg not in [-360, 360]";
  if (!std::isfinite(f.pos.h_m) || f.pos.h_m < kMinPlausibleHeight_m || f.pos.h_m > kMaxPlausibleHeight_m)
    return "height " + six_significant(f.pos.h_m) + " m not in [" + six_significant(kMinPlausibleHeight_m) + ", " +
           six_significant(kMaxPlausibleHeight_m) + "]";
  if (!pos_cov_ned_m2.allFinite() || !(pos_cov_ned_m2.diagonal().array() > 0.0).all() ||
      !(pos_cov_ned_m2.diagonal().array() <= kMaxPlausiblePositionVariance_m2).all())
    return "position variances (" + six_significant(pos_cov_ned_m2(0, 0)) + ", " +
           six_significant(pos_cov_ned_m2(1, 1)) + ", " + six_significant(pos_cov_ned_m2(2, 2)) +
           ") m^2 not positive, finite and below " + six_significant(kMaxPlausiblePositionVariance_m2);
  // Positive-definite after scaling by the diagonal (a correlation matrix): a variance of 1e-300 beside 1 m^2
  // must not fail for rounding alone.
  {
    const Vec3 inv_std = pos_cov_ned_m2.diagonal().cwiseSqrt().cwiseInverse();
    const Mat3 corr = inv_std.asDiagonal() * pos_cov_ned_m2 * inv_std.asDiagonal();
    if (!corr.allFinite() || (corr - corr.transpose()).cwiseAbs().maxCoeff() > 1e-6 ||
        Eigen::SelfAdjointEigenSolver<Mat3>(corr).eigenvalues().minCoeff() <= 0.0)
      return "position covariance not symmetric positive-definite";
  }
  if (!f.pos_std_ned_m.allFinite() || !(f.pos_std_ned_m.array() > 0.0).all())
    return "position std not positive and finite";
  if (f.has_velocity) {
    if (!f.vel_n_mps.allFinite() || f.vel_n_mps.norm() > kMaxPlausibleSpeed_mps)
      return "velocity " + six_significant(f.vel_n_mps.norm()) + " m/s not finite below " +
             six_significant(kMaxPlausibleSpeed_mps);
    if (!f.vel_std_n_mps.allFinite() || !(f.vel_std_n_mps.array() >= 0.0).all() ||
        !(f.vel_std_n_mps.array() < kMaxPlausibleSpeed_mps).all())
      return "velocity std (" + six_significant(f.vel_std_n_mps[0]) + ", " + six_significant(f.vel_std_n_mps[1]) +
             ", " + six_significant(f.vel_std_n_mps[2]) + ") m/s not finite in [0, " +
             six_significant(kMaxPlausibleSpeed_mps) + ")";
  }
  if (!std::isfinite(f.age_s) || !std::isfinite(f.ratio) || f.num_sats < 0)
    return "age, ratio or satellite count not finite and >= 0";
  return std::nullopt;
}
}  // namespace

std::optional<std::string> implausibility(const GnssSolution& s) {
  if (auto why = implausibility(s.time)) return why;
  return fix_implausibility(s.fix, s.pos_cov_ned_m2);
}

std::optional<std::string> implausibility(const GnssFix& fix) {
  return fix_implausibility(fix, fix.pos_std_ned_m.cwiseAbs2().asDiagonal().toDenseMatrix());
}

std::optional<std::string> implausibility(const PpsTimeLabel& label) {
  if (auto why = implausibility(label.pulse_time)) return why;
  if (label.quantization_error_valid && !std::isfinite(label.quantization_error_s))
    return "quantisation error not finite";
  return std::nullopt;
}

}  // namespace ldv::gnss
