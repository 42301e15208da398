#pragma once
// The IMU's white noise as installed, from a standstill in the data: an engine idling and a vehicle body
// shaking make it many times the datasheet's. A standstill is where the GNSS track does not move for a
// while (the IMU's own static detector cannot be trusted for this: its thresholds come from the very
// noise in question); over it, the median PSD of each axis's rate between 0.5 and 40 Hz gives its
// white-noise density (an engine's harmonics, 25 Hz and up, fill the sample-to-sample scatter but take few
// bins, and integrate to nothing).
#include <cmath>
#include <vector>

#include "common/formats/nav_types.hpp"
#include "estimator/filter/imu_noise_scale.hpp"

namespace ldv::est {

struct InstalledImuNoise {
  bool found = false;  // a standstill of at least min_standstill_s
  double standstill_s = 0.0;
  Vec3 arw_rad_per_sqrt_s = Vec3::Zero();  // gyro white-noise density measured per axis
  Vec3 vrw_mps_per_sqrt_s = Vec3::Zero();  // accel
  // What the ZUPT's static detector sees at rest: the median over kSpecificForceWindow_s windows of the std of
  // |f| [m/s^2]. The white noise and an engine's harmonics together (the densities above are the white part
  // only: at idle the harmonics scatter a tactical IMU's |f| several times beyond it).
  static constexpr double kSpecificForceWindow_s = 0.5;
  double f_norm_scatter_mps2 = 0.0;
  // The relative 1-sigma of each axis's measured PSD (the median of the periodogram's bins: a few % over 10 s).
  double psd_relative_sigma = NAN;
  // The factors on the configured PSDs that cover the measured noise, gyro and accel apart (each the median
  // over axes of the squared density ratio; at least 1).
  ImuNoiseScale psd_scale(const Vec3& arw_configured, const Vec3& vrw_configured) const;
  // The 1-sigma of those factors as measured (before the floor of 1; NaN without a standstill).
  ImuNoiseScale psd_scale_sigma(const Vec3& arw_configured, const Vec3& vrw_configured) const;
  // The factors as measured, below 1 too.
  ImuNoiseScale psd_scale_unbounded(const Vec3& arw_configured, const Vec3& vrw_configured) const;
};

// imu and gnss in time order on one time base; the standstill: GNSS horizontal speed below max_speed_mps over
// 1 s, beyond the noise of the fixes' stated std.
InstalledImuNoise measure_installed_imu_noise(const std::vector<ImuIncrement>& imu, const std::vector<GnssFix>& gnss,
                                              double min_standstill_s = 5.0, double max_speed_mps = 0.05);

}  // namespace ldv::est
