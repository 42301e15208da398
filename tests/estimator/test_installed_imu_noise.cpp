// The IMU noise as installed (estimator/calibrate/installed_imu_noise.hpp), against the simulator's
// vibration: white noise at 10x the datasheet's, measured over the GNSS standstill of the start.
#include <gtest/gtest.h>

#include "estimator/calibrate/installed_imu_noise.hpp"
#include "estimator/run/run_navigation.hpp"
#include "sim/simulator.hpp"

namespace ldv::est {
namespace {

sim::SimResult vibrating_car(double gnss_rate_hz) {
  sim::SimRequest req;
  req.grade = "3dm-gx2";
  req.scenario = "straight";  // 10 s at rest, then straight runs
  req.duration_s = 60.0;
  req.gnss_rate_hz = gnss_rate_hz;
  req.seed = 4;
  req.vehicle.vibration_factor = 10.0;
  req.vehicle.engine_accel_mps2 = 0.0;  // white only: the closed form below
  req.vehicle.engine_gyro_dps = 0.0;
  return sim::simulate(req);
}

TEST(InstalledImuNoise,
     GivenAStandstillWithVibration_WhenTheGnssComesAtOneOrFourHz_ThenTheNoiseIsTenTimesTheDatasheet) {
  for (const double rate_hz : {1.0, 4.0}) {
    SCOPED_TRACE(rate_hz);
    const sim::SimResult sim = vibrating_car(rate_hz);
    const FilterOptions datasheet = options_from_kfgins(sim.kfgins);
    const InstalledImuNoise noise = measure_installed_imu_noise(sim.imu, sim.gnss);
    // At 4 Hz the chord between consecutive RTK fixes alone moves at ~0.1 m/s: a standstill is judged over 1 s.
    ASSERT_TRUE(noise.found);
    EXPECT_GT(noise.standstill_s, 8.0);
    EXPECT_LT(noise.standstill_s, 12.0);
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(noise.arw_rad_per_sqrt_s(k) / datasheet.arw_rad_per_sqrt_s(k), 10.0, 1.0) << "gyro " << k;
      EXPECT_NEAR(noise.vrw_mps_per_sqrt_s(k) / datasheet.vrw_mps_per_sqrt_s(k), 10.0, 1.0) << "accel " << k;
    }
    // The PSD scale: (10x)^2, from the per-sample scatter (the 8 s give ~1 % on a variance of 800 samples).
    EXPECT_NEAR(noise.psd_scale(datasheet.arw_rad_per_sqrt_s, datasheet.vrw_mps_per_sqrt_s), 100.0, 15.0);
  }
}

TEST(InstalledImuNoise, GivenADriveWithoutAStop_ThenNoStandstillIsFound) {
  sim::SimRequest req;
  req.grade = "3dm-gx2";
  req.scenario = "turns";
  req.duration_s = 60.0;
  req.gnss_rate_hz = 4.0;
  req.seed = 4;
  req.vehicle.vibration_factor = 10.0;
  sim::SimResult sim = sim::simulate(req);
  std::vector<GnssFix> moving;
  for (const GnssFix& f : sim.gnss)
    if (f.t_s - sim.imu.front().t_s > 17.0)
      moving.push_back(f);  // after the start's 10 s at rest and the 6 s acceleration
  const InstalledImuNoise noise = measure_installed_imu_noise(sim.imu, moving);
  EXPECT_FALSE(noise.found) << noise.standstill_s << " s from " << moving.front().t_s - sim.imu.front().t_s;
}

}  // namespace
}  // namespace ldv::est
