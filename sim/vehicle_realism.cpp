#include "sim/vehicle_realism.hpp"

#include <cmath>

#include "common/io/input_error.hpp"
#include "common/io/number_text.hpp"
#include "sim/random.hpp"

namespace ldv::sim {
namespace {

void require(bool ok, const std::string& option, const std::string& expected, double found) {
  if (!ok) throw InputError(option, 0, "expected " + expected + ", found " + six_significant(found));
}
bool in(double v, double lo, double hi) { return std::isfinite(v) && v >= lo && v <= hi; }

// The realism preset: the magnitudes a typical car installation shows.
constexpr double kRealismVibrationFactor = 10.0;
constexpr double kRealismShocksPerKm = 2.0;
constexpr double kRealismMaxImuLatency_s = 0.3;
constexpr double kRealismMisalignment_deg = 2.0;  // per axis, uniform +-
constexpr double kRealismGnssVelocityLag_s = 0.1;
constexpr double kRealismGnssVelocityNoiseFactor = 3.0;
constexpr double kRealismGnssOutlierRate = 0.005;

}  // namespace

std::vector<Vec3> axis_aligned_mountings_deg() {
  // Six ways up (z down, z up = upside down, z along +-x, z along +-y), each at four headings.
  const Vec3 ups[6] = {{0, 0, 0}, {180, 0, 0}, {90, 0, 0}, {-90, 0, 0}, {0, 90, 0}, {0, -90, 0}};
  std::vector<Vec3> out;
  for (double yaw : {0.0, 90.0, 180.0, -90.0})
    for (const Vec3& u : ups) out.push_back(Vec3(u.x(), u.y(), yaw));
  return out;
}

VehicleRealism resolve_vehicle_options(const VehicleOptions& o, uint64_t seed) {
  if (o.realism != "none" && o.realism != "vehicle")
    throw InputError("--realism", 0, "unknown realism '" + o.realism + "': expected none or vehicle");
  VehicleRealism r;
  r.realism_vehicle = o.realism == "vehicle";
  const bool preset = r.realism_vehicle;

  if (o.vibration_factor) {
    require(in(*o.vibration_factor, 1.0, 1000.0), "--vibration",
            "a factor in [1, 1000] (installed white noise / the grade's)", *o.vibration_factor);
    r.vibration_factor = *o.vibration_factor;
  } else if (preset) {
    r.vibration_factor = kRealismVibrationFactor;
  }
  require(in(o.engine_accel_mps2, 0.0, 50.0), "--engine-vibration", "an accelerometer amplitude in [0, 50] m/s^2",
          o.engine_accel_mps2);
  require(in(o.engine_gyro_dps, 0.0, 100.0), "--engine-vibration", "a gyro amplitude in [0, 100] deg/s",
          o.engine_gyro_dps);
  if (r.vibration_factor > 0) {
    r.engine_accel_mps2 = o.engine_accel_mps2;
    r.engine_gyro_rad_s = o.engine_gyro_dps * kDegToRad;
  }

  if (o.shocks_per_km) {
    require(in(*o.shocks_per_km, 0.0, 1000.0), "--shocks", "a rate in [0, 1000] bumps per km", *o.shocks_per_km);
    r.shocks_per_km = *o.shocks_per_km;
  } else if (preset) {
    r.shocks_per_km = kRealismShocksPerKm;
  }

  if (o.imu_latency_s) {
    require(in(*o.imu_latency_s, 0.0, 1.0), "--imu-latency", "a latency in [0, 1] s", *o.imu_latency_s);
    r.imu_latency_s = *o.imu_latency_s;
  } else if (preset) {
    Rng rng(seed, "realism_imu_latency");
    r.imu_latency_s = kRealismMaxImuLatency_s * rng.uniform();
  }

  // A host that tags samples when it reads them (not drawn by the preset: a car's IMU is read on its own clock).
  if (o.imu_stamp_jitter_s) {
    require(in(*o.imu_stamp_jitter_s, 0.0, 0.01), "--imu-stamp-jitter", "a std in [0, 0.01] s", *o.imu_stamp_jitter_s);
    r.imu_stamp_jitter_s = *o.imu_stamp_jitter_s;
  }

  if (o.mounting_rpy_deg) {
    const Vec3& m = *o.mounting_rpy_deg;
    require(in(m.x(), -180.0, 180.0), "--mounting", "roll in [-180, 180] deg", m.x());
    require(in(m.y(), -90.0, 90.0), "--mounting", "pitch in [-90, 90] deg", m.y());
    require(in(m.z(), -180.0, 180.0), "--mounting", "yaw in [-180, 180] deg", m.z());
    r.mounted = true;
    r.mounting_rpy_rad = m * kDegToRad;
  } else if (preset) {
    Rng rng(seed, "realism_mounting");
    const auto all = axis_aligned_mountings_deg();
    const size_t pick = std::min(all.size() - 1, static_cast<size_t>(rng.uniform() * all.size()));
    Vec3 m = all[pick];
    for (int i = 0; i < 3; ++i) m[i] += kRealismMisalignment_deg * (2.0 * rng.uniform() - 1.0);
    r.mounted = true;
    r.mounting_rpy_rad = m * kDegToRad;
  }
  if (r.mounted) r.C_b_v = C_b_n_from_euler(r.mounting_rpy_rad);

  if (o.gnss_velocity_lag_s) {
    require(in(*o.gnss_velocity_lag_s, 0.0, 5.0), "--gnss-velocity-lag", "a lag in [0, 5] s", *o.gnss_velocity_lag_s);
    r.gnss_velocity_lag_s = *o.gnss_velocity_lag_s;
  } else if (preset) {
    r.gnss_velocity_lag_s = kRealismGnssVelocityLag_s;
  }
  if (o.gnss_velocity_noise_factor) {
    require(in(*o.gnss_velocity_noise_factor, 0.0, 100.0), "--gnss-velocity-noise",
            "a factor in [0, 100] (simulated velocity noise / stated std)", *o.gnss_velocity_noise_factor);
    r.gnss_velocity_noise_factor = *o.gnss_velocity_noise_factor;
  } else if (preset) {
    r.gnss_velocity_noise_factor = kRealismGnssVelocityNoiseFactor;
  }
  if (o.gnss_outlier_rate) {
    require(in(*o.gnss_outlier_rate, 0.0, 1.0), "--gnss-outliers", "a fraction of epochs in [0, 1]",
            *o.gnss_outlier_rate);
    r.gnss_outlier_rate = *o.gnss_outlier_rate;
  } else if (preset) {
    r.gnss_outlier_rate = kRealismGnssOutlierRate;
  }

  r.odometer = o.odometer || preset;
  require(in(o.odo_rate_hz, 0.1, 1000.0), "--odo-rate", "an odometer rate in [0.1, 1000] Hz", o.odo_rate_hz);
  for (int i = 0; i < 3; ++i)
    require(in(o.odo_lever_arm_b_m[i], -100.0, 100.0), "--odo-lever-arm",
            "x,y,z within +-100 m (odometer point minus IMU, IMU body axes)", o.odo_lever_arm_b_m[i]);
  require(in(o.odo_noise_mps, 0.0, 10.0), "--odo-noise", "a white-noise std in [0, 10] m/s", o.odo_noise_mps);
  require(in(o.odo_quantum_mps, 0.0, 10.0), "--odo-quantum", "a speed resolution in [0, 10] m/s (0: none)",
          o.odo_quantum_mps);
  r.odo_rate_hz = o.odo_rate_hz;
  r.odo_lever_arm_b_m = o.odo_lever_arm_b_m;
  r.odo_noise_mps = o.odo_noise_mps;
  r.odo_quantum_mps = o.odo_quantum_mps;

  require(in(o.wheel_slip_deg_per_mps2, -5.0, 5.0), "--wheel-slip",
          "a side slip in [-5, 5] deg per m/s^2 of lateral acceleration", o.wheel_slip_deg_per_mps2);
  r.wheel_slip_rad_per_mps2 = o.wheel_slip_deg_per_mps2 * kDegToRad;
  r.write_datasheet_config = preset;
  return r;
}

const EffectInfo* find_realism_quantity(const std::string& name) {
  static const std::vector<EffectInfo> table = {
      {"vibration_white_factor", {1}, {"-"}, {1.0}, {}, "installed white noise / the grade's ARW and VRW"},
      {"installed_arw",
       {3},
       {"deg/sqrt(h)", "deg/sqrt(h)", "deg/sqrt(h)"},
       std::vector<double>(3, kDegToRad / 60.0),
       {},
       "gyro white noise of the installed IMU (grade ARW x factor), body axes"},
      {"installed_vrw",
       {3},
       {"m/s/sqrt(h)", "m/s/sqrt(h)", "m/s/sqrt(h)"},
       std::vector<double>(3, 1.0 / 60.0),
       {},
       "accelerometer white noise of the installed IMU (grade VRW x factor), body axes"},
      {"engine_vibration",
       {5},
       {"m/s^2", "deg/s", "Hz", "Hz", "m/s"},
       {1.0, kDegToRad, 1.0, 1.0, 1.0},
       {},
       "engine harmonic: accel amplitude (vehicle z; x, y half), gyro amplitude (vehicle x, y; z half), "
       "frequency at rest, frequency at and above the speed of the last value"},
      {"shocks", {1}, {"1/km"}, {1e-3}, {}, "road bumps per km travelled"},
      {"imu_latency", {1}, {"s"}, {1.0}, {}, "IMU time tag minus true sample time"},
      {"imu_stamp_jitter", {1}, {"s"}, {1.0}, {}, "std of the IMU time tags about the sample times (uniform)"},
      {"vehicle_mounting",
       {3},
       {"deg", "deg", "deg"},
       std::vector<double>(3, kDegToRad),
       {},
       "IMU body in the vehicle frame: C_b_v = Rz(yaw) Ry(pitch) Rx(roll), roll pitch yaw"},
      {"gnss_velocity_lag", {1}, {"s"}, {1.0}, {}, "GNSS velocity is the true one at epoch - lag"},
      {"gnss_velocity_noise_factor", {1}, {"-"}, {1.0}, {}, "simulated GNSS velocity noise / stated std"},
      {"gnss_outliers", {1}, {"-"}, {1.0}, {}, "fraction of epochs with a 1-3 m position jump"},
      {"odometer_lever_arm",
       {3},
       {"m", "m", "m"},
       std::vector<double>(3, 1.0),
       {},
       "odometer point (rear-axle centre) minus IMU, IMU body axes"},
      {"odometer_noise", {1}, {"m/s"}, {1.0}, {}, "odometer white noise std"},
      {"odometer_quantum", {1}, {"m/s"}, {1.0}, {}, "odometer speed resolution"},
      {"wheel_slip", {1}, {"deg/(m/s^2)"}, {kDegToRad}, {}, "side slip angle per lateral acceleration"},
  };
  for (const auto& e : table)
    if (e.name == name) return &e;
  return nullptr;
}

}  // namespace ldv::sim
