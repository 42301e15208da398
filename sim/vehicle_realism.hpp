#pragma once
// `ldv sim --realism vehicle` and the options it turns on: what a real car does to an installed IMU,
// a GNSS receiver and an odometer (vibration, road shocks, IMU latency, a rotated mounting, lagged and
// noisier GNSS velocity, GNSS outliers, an odometer). Each is usable alone; the realism preset fills
// every option not given with a seeded draw (one random stream per quantity). sim/README.md.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/math/rotation.hpp"
#include "sim/effects.hpp"

namespace ldv::sim {

// As requested (engineering units at the edges, as on the command line). Unset = off, or drawn by
// `realism = "vehicle"`.
struct VehicleOptions {
  std::string realism = "none";                      // none | vehicle
  std::optional<double> vibration_factor;            // installed white noise = factor x the grade's ARW/VRW (>= 1)
  double engine_accel_mps2 = 0.3;                    // engine harmonic amplitude, vehicle z (x, y: half)
  double engine_gyro_dps = 0.2;                      // engine harmonic amplitude, vehicle x and y (z: half)
  std::optional<double> shocks_per_km;               // road bumps per km travelled
  std::optional<double> imu_latency_s;               // IMU time tag = true sample time + latency
  std::optional<double> imu_stamp_jitter_s;          // IMU time tags scattered about the sample times (std, uniform)
  std::optional<Vec3> mounting_rpy_deg;              // C_b_v = Rz(yaw) Ry(pitch) Rx(roll)
  std::optional<double> gnss_velocity_lag_s;         // GNSS velocity is the one at epoch - lag
  std::optional<double> gnss_velocity_noise_factor;  // simulated velocity noise / stated std
  std::optional<double> gnss_outlier_rate;           // fraction of epochs with a 1-3 m jump
  bool odometer = false;                             // write odo.txt
  double odo_rate_hz = 50.0;
  Vec3 odo_lever_arm_b_m = Vec3::Zero();  // odometer point (rear-axle centre) minus IMU, IMU body axes
  double odo_noise_mps = 0.02;            // white noise std per sample
  double odo_quantum_mps = 0.0;           // speed resolution (0: none)
  double wheel_slip_deg_per_mps2 = 0.0;   // side slip per lateral acceleration (0: none)
};

// Resolved, SI, every quantity decided (0 = off). Built by resolve_vehicle_options.
struct VehicleRealism {
  bool realism_vehicle = false;
  double vibration_factor = 0.0;  // 0: no vibration
  double engine_accel_mps2 = 0.0, engine_gyro_rad_s = 0.0;
  double shocks_per_km = 0.0;
  double imu_latency_s = 0.0;
  double imu_stamp_jitter_s = 0.0;
  bool mounted = false;
  Vec3 mounting_rpy_rad = Vec3::Zero();
  Mat3 C_b_v = Mat3::Identity();
  double gnss_velocity_lag_s = 0.0;
  double gnss_velocity_noise_factor = 1.0;
  double gnss_outlier_rate = 0.0;
  bool odometer = false;
  double odo_rate_hz = 50.0;
  Vec3 odo_lever_arm_b_m = Vec3::Zero();
  double odo_noise_mps = 0.0, odo_quantum_mps = 0.0;
  double wheel_slip_rad_per_mps2 = 0.0;
  bool write_datasheet_config = false;
};

// Checks every option (InputError naming the option and what was expected) and fills the unset ones
// from the realism preset's draws (streams "realism_<quantity>" of the seed).
VehicleRealism resolve_vehicle_options(const VehicleOptions& o, uint64_t seed);

// The 24 axis-aligned mountings as roll, pitch, yaw [deg] (yaw 0/90/180/-90 times six ways up).
std::vector<Vec3> axis_aligned_mountings_deg();

// Units of the quantities this adds to truth_effects.yaml (same layout as effect_table()).
const EffectInfo* find_realism_quantity(const std::string& name);

}  // namespace ldv::sim
