#pragma once
// Factors on the configured IMU white-noise PSDs (ARW^2, VRW^2), gyro and accelerometer apart: an installed
// IMU's vibration is seldom the same multiple of the datasheet on both, and a position NIS cannot tell them
// apart (on a tactical IMU at 4 Hz it is held by the accelerometers' share alone, leaving the attitude 10x
// overconfident when the gyros vibrate as much).
#include <algorithm>

namespace ldv::est {

struct ImuNoiseScale {
  double gyro = 1.0, accel = 1.0;
  double larger() const { return std::max(gyro, accel); }
};

}  // namespace ldv::est
