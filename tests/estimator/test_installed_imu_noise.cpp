// The IMU noise as installed (estimator/calibrate/installed_imu_noise.hpp), against the simulator's
// vibration: white noise at 10x the datasheet's, measured over the GNSS standstill of the start.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "estimator/calibrate/installed_imu_noise.hpp"
#include "estimator/filter/nav_filter.hpp"
#include "estimator/run/nav_session.hpp"
#include "estimator/run/run_navigation.hpp"
#include "sim/simulator.hpp"
#include "tests/estimator/sim_run.hpp"

namespace ldv::est {
namespace {

sim::SimResult vibrating_car(double gnss_rate_hz, double duration_s = 60.0) {
  sim::SimRequest req;
  req.grade = "3dm-gx2-typical";
  req.scenario = "straight";  // 10 s at rest, then straight runs
  req.duration_s = duration_s;
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
    // The PSD scales: (10x)^2, from the periodogram's median over ~900 bins of the 8 s (~5 % on a PSD).
    const ImuNoiseScale psd = noise.psd_scale(datasheet.arw_rad_per_sqrt_s, datasheet.vrw_mps_per_sqrt_s);
    EXPECT_NEAR(psd.gyro, 100.0, 15.0);
    EXPECT_NEAR(psd.accel, 100.0, 15.0);
  }
}

// The measured noise comes with its sigma (issue 48, item 5): over independent standstills, each axis's PSD ratio
// scatters about the simulated 100x by its stated sigma (z RMS within 0.7-1.4: 90 draws put the RMS within 0.15 of
// its truth at 2 sigma). The factors (the median of the three axes, sigma stated as one axis's) scatter less.
TEST(InstalledImuNoise, GivenManyStandstills_ThenTheMeasuredPsdScattersByItsStatedSigma) {
  constexpr int kDraws = 15;
  double z2_axis = 0.0, z2_factor = 0.0;
  int n_axis = 0, n_factor = 0;
  double mean_relative_sigma = 0.0;
  for (int seed = 1; seed <= kDraws; ++seed) {
    sim::SimRequest req;
    req.grade = "3dm-gx2-typical";
    req.scenario = "straight";  // 10 s at rest first
    req.duration_s = 20.0;
    req.gnss_rate_hz = 4.0;
    req.seed = static_cast<unsigned>(300 + seed);
    req.vehicle.vibration_factor = 10.0;  // installed N = 10x the grade's: PSD 100x
    req.vehicle.engine_accel_mps2 = 0.0;
    req.vehicle.engine_gyro_dps = 0.0;
    const sim::SimResult sim = sim::simulate(req);
    const FilterOptions datasheet = options_from_kfgins(sim.kfgins);
    const InstalledImuNoise noise = measure_installed_imu_noise(sim.imu, sim.gnss);
    ASSERT_TRUE(noise.found) << seed;
    ASSERT_TRUE(noise.psd_relative_sigma > 0.0) << seed;
    mean_relative_sigma += noise.psd_relative_sigma / kDraws;
    for (int k = 0; k < 3; ++k) {
      const double gyro = std::pow(noise.arw_rad_per_sqrt_s(k) / datasheet.arw_rad_per_sqrt_s(k), 2);
      const double accel = std::pow(noise.vrw_mps_per_sqrt_s(k) / datasheet.vrw_mps_per_sqrt_s(k), 2);
      for (const double ratio : {gyro, accel}) {
        const double z = (ratio - 100.0) / (100.0 * noise.psd_relative_sigma);
        z2_axis += z * z;
        ++n_axis;
      }
    }
    const ImuNoiseScale factor = noise.psd_scale(datasheet.arw_rad_per_sqrt_s, datasheet.vrw_mps_per_sqrt_s);
    const ImuNoiseScale sigma = noise.psd_scale_sigma(datasheet.arw_rad_per_sqrt_s, datasheet.vrw_mps_per_sqrt_s);
    z2_factor += std::pow((factor.gyro - 100.0) / sigma.gyro, 2) + std::pow((factor.accel - 100.0) / sigma.accel, 2);
    n_factor += 2;
  }
  const double rms_axis = std::sqrt(z2_axis / n_axis), rms_factor = std::sqrt(z2_factor / n_factor);
  std::printf("[ info ] relative sigma %.3f; z RMS per axis %.2f (%d), of the factors %.2f (%d)\n", mean_relative_sigma,
              rms_axis, n_axis, rms_factor, n_factor);
  EXPECT_GT(rms_axis, 0.7);
  EXPECT_LT(rms_axis, 1.4);
  EXPECT_LT(rms_factor, 1.2);  // stated as one axis's: never overconfident
  EXPECT_GT(rms_factor, 0.4);  // nor idle: the median of three equal axes scatters 0.67 of one
}

// RTK at 1 Hz: the track moves by its own noise between fixes (2 cm horizontal, 2-3 cm vertical per fix: a
// 1 s chord of 3-4 cm/s, beyond 5 cm/s in one chord in five). The standstill is judged against that noise,
// so a 10 s stop is found on every seed, not only on those whose chords all stayed under 5 cm/s.
TEST(InstalledImuNoise, GivenOneHzRtk_ThenTheStandstillIsFoundWhateverTheNoiseOfItsChords) {
  int found = 0;
  constexpr int kSeeds = 12;
  for (int seed = 1; seed <= kSeeds; ++seed) {
    sim::SimRequest req;
    req.grade = "3dm-gx2-typical";
    req.scenario = "straight";  // 10 s at rest first
    req.duration_s = 20.0;
    req.gnss_rate_hz = 1.0;
    req.seed = static_cast<unsigned>(100 + seed);
    req.vehicle.vibration_factor = 10.0;
    const sim::SimResult sim = sim::simulate(req);
    const InstalledImuNoise noise = measure_installed_imu_noise(sim.imu, sim.gnss);
    if (noise.found && noise.standstill_s > 8.0 && noise.standstill_s < 12.0) ++found;
  }
  EXPECT_EQ(found, kSeeds);
}

TEST(InstalledImuNoise, GivenADriveWithoutAStop_ThenNoStandstillIsFound) {
  sim::SimRequest req;
  req.grade = "3dm-gx2-typical";
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

// Engine harmonics (tens of Hz, 0.3 m/s^2 and 0.2 deg/s: the simulator's default) fill the sample-to-sample
// scatter but integrate to nothing: the measured white noise stays that of the broadband vibration (the
// scatter read the accelerometers' as 3x their true density, 320x their datasheet PSD instead of 100x).
TEST(InstalledImuNoise, GivenEngineHarmonicsOnTopOfTheVibration_ThenTheWhiteNoiseIsStillTenTimesTheDatasheet) {
  sim::SimRequest req;
  req.grade = "hg1700-typical";  // a small white noise: the harmonics would dominate the scatter
  req.scenario = "straight";
  req.duration_s = 60.0;
  req.gnss_rate_hz = 4.0;
  req.seed = 5;
  req.vehicle.vibration_factor = 10.0;  // engine harmonics at their defaults
  const sim::SimResult sim = sim::simulate(req);
  const FilterOptions datasheet = options_from_kfgins(sim.kfgins);
  const InstalledImuNoise noise = measure_installed_imu_noise(sim.imu, sim.gnss);
  ASSERT_TRUE(noise.found);
  const ImuNoiseScale psd = noise.psd_scale(datasheet.arw_rad_per_sqrt_s, datasheet.vrw_mps_per_sqrt_s);
  std::printf("[ info ] PSD scales with engine harmonics: gyro %.0fx, accel %.0fx (white: 100x)\n", psd.gyro,
              psd.accel);
  EXPECT_GT(psd.gyro, 75.0);
  EXPECT_LT(psd.gyro, 140.0);
  EXPECT_GT(psd.accel, 75.0);
  EXPECT_LT(psd.accel, 140.0);
}

// The paper's quantisation (a white error of the integrated angle and velocity, rate density rising as f^2) is not
// white noise: it integrates to nothing. On the paper's HG1700 (gyro Q 6-17 arcsec, accelerometer Q 0.35-0.88 m/h,
// both far above N at every frequency of the band) the median of the bins read it as 600-700x the ARW and 520x the
// VRW, and ldv nav's default run then drifted up to 3.5x further in outages than with the configured model. Split
// off, what is left is within a few times the configured white noise (2.5x and 4.4x the PSD: at the band's lowest
// bins the white part is 3 % of the quantisation's, 8 s of standstill cannot resolve it better). Under 10x
// vibration the vibration's white noise (100x the PSD) is found: 119x and 101x.
TEST(InstalledImuNoise, GivenTheQuantisationOfThePapersHg1700_ThenItIsNotTakenForWhiteNoise) {
  for (const double vibration : {0.0, 10.0}) {
    sim::SimRequest req;
    req.grade = "hg1700-paper";
    req.scenario = "straight";
    req.duration_s = 60.0;
    req.gnss_rate_hz = 4.0;
    req.seed = 5;
    if (vibration > 0) {
      req.vehicle.vibration_factor = vibration;
      req.vehicle.engine_accel_mps2 = 0.0;
      req.vehicle.engine_gyro_dps = 0.0;
    }
    const sim::SimResult sim = sim::simulate(req);
    const FilterOptions configured = options_from_kfgins(sim.kfgins);  // the grade's own N
    const InstalledImuNoise noise = measure_installed_imu_noise(sim.imu, sim.gnss);
    ASSERT_TRUE(noise.found);
    const ImuNoiseScale psd = noise.psd_scale(configured.arw_rad_per_sqrt_s, configured.vrw_mps_per_sqrt_s);
    std::printf("[ info ] hg1700-paper, vibration %.0fx: PSD scales gyro %.1fx, accel %.1fx\n", vibration, psd.gyro,
                psd.accel);
    if (vibration == 0.0) {
      EXPECT_LT(psd.gyro, 10.0);
      EXPECT_LT(psd.accel, 10.0);
    } else {  // the vibration's white noise (100x the PSD) stands out of the quantisation at the low bands
      EXPECT_GT(psd.gyro, 50.0);
      EXPECT_LT(psd.gyro, 200.0);
      EXPECT_GT(psd.accel, 50.0);
      EXPECT_LT(psd.accel, 200.0);
    }
  }
}

// A datasheet that prints no VRW (the paper's three do not), written as vrw 0: the floor is a factor on the
// configured PSD and cannot raise a 0, so the filter trusted every accelerometer increment exactly. The
// standstill's measurement takes the 0's place (NavFilter::fill_unset_white_noise), and the run says so.
TEST(InstalledImuNoise, GivenAVrwOfZeroInTheConfiguration_ThenTheStandstillsMeasurementTakesItsPlace) {
  const sim::SimResult sim = vibrating_car(1.0, 120.0);
  const FilterOptions datasheet = options_from_kfgins(sim.kfgins);
  FilterOptions no_vrw = datasheet;
  no_vrw.vrw_mps_per_sqrt_s.setZero();

  NavFilter filter(no_vrw);
  KfGinsConfig cfg = sim.kfgins;
  cfg.end_time_s = -1;
  const RunSummary sum = run_navigation(sim.imu, sim.gnss, cfg, filter, {});
  std::printf("%s\n", sum.white_noise_filled.c_str());
  EXPECT_NE(sum.white_noise_filled.find("imunoise.vrw"), std::string::npos);
  EXPECT_EQ(sum.white_noise_filled.find("imunoise.arw"), std::string::npos) << "the ARW was configured";
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(filter.options().vrw_mps_per_sqrt_s(k) / datasheet.vrw_mps_per_sqrt_s(k), 10.0, 1.5) << k;
    EXPECT_EQ(filter.options().arw_rad_per_sqrt_s(k), datasheet.arw_rad_per_sqrt_s(k)) << k;
  }
  EXPECT_NEAR(sum.imu_noise_floor.accel, 1.0, 0.15) << "measured against itself";

  // Against the truth: the filled run is as consistent as one configured with the installed VRW (10x the
  // datasheet's, as simulated); with the 0 kept (no floor) the filter is overconfident in velocity.
  FilterOptions installed = datasheet, kept = no_vrw;
  installed.vrw_mps_per_sqrt_s *= 10.0;
  kept.installed_noise_floor = false;
  const test::Accuracy filled = test::evaluate(sim, no_vrw, 20.0), right = test::evaluate(sim, installed, 20.0),
                       zero = test::evaluate(sim, kept, 20.0);
  std::printf("velocity NEES (3 dof): VRW measured %.2f, VRW as installed %.2f, VRW 0 kept %.2f\n", filled.nees_vel,
              right.nees_vel, zero.nees_vel);
  EXPECT_NEAR(filled.nees_vel / right.nees_vel, 1.0, 0.2);
  EXPECT_GT(zero.nees_vel, 1.5 * right.nees_vel);
}

// A session fed as a live service feeds it (fixes 0.3 s after their epoch, no initial state: aligned from the
// data): the mean velocity error over the filter's own sigma, squared (per dof, 1 Hz after 20 s of navigation).
struct NoiseFloorLiveRun {
  std::string how;
  FilterOptions options;
  ImuNoiseScale floor;
  double vel_nees_per_dof = 0.0;
  FaultCounters faults;
};
NoiseFloorLiveRun run_live_noise_floor(const sim::SimResult& sim, const FilterOptions& fo) {
  KfGinsConfig cfg = sim.kfgins;
  cfg.init_pos.reset();
  cfg.init_vel_n_mps.reset();
  cfg.init_rpy_rad.reset();
  NavFilter filter(fo);
  NavSession session(session_options_from(cfg, fo), filter, nullptr);
  double sum = 0.0, next_s = 0.0;
  long n = 0;
  size_t g = 0, t = 0;
  for (const ImuIncrement& inc : sim.imu) {
    for (; g < sim.gnss.size() && sim.gnss[g].t_s + 0.3 <= inc.t_s; ++g) session.add_gnss(sim.gnss[g], inc.t_s);
    session.add_imu(inc, 2300, inc.t_s);
    if (!session.navigating() || filter.state().t_s < session.started_at_s() + 20.0 || filter.state().t_s < next_s)
      continue;
    next_s = filter.state().t_s + 1.0;
    while (t + 1 < sim.truth.size() && sim.truth[t].t_s < filter.state().t_s - 1e-6) ++t;
    const Vec3 e = test::nav_error(filter.state(), sim.truth[t]).segment<3>(3);
    sum += e.cwiseQuotient(filter.nav_std().vel_n_mps).squaredNorm() / 3.0;
    ++n;
  }
  session.finish();
  return {session.initialisation(), filter.options(), filter.imu_noise_floor(), n > 0 ? sum / n : 1e9, filter.faults()};
}

// Live there is no file to measure the installed noise over before the start: the session measures the standstill
// before its alignment. A VRW configured as 0 takes its measurement and the gyro floor is set, as `ldv nav` does
// over the file; before, the live filter started from the configuration (with a 0 it trusted every accelerometer
// increment exactly, velocity NEES 47-71).
TEST(InstalledImuNoise, GivenALiveSession_ThenTheStandstillBeforeTheStartSetsTheFloorAndFillsAZeroVrw) {
  const sim::SimResult sim = vibrating_car(1.0, 120.0);
  const FilterOptions datasheet = options_from_kfgins(sim.kfgins);
  FilterOptions no_vrw = datasheet;
  no_vrw.vrw_mps_per_sqrt_s.setZero();
  const NoiseFloorLiveRun filled = run_live_noise_floor(sim, no_vrw);
  std::printf("%s\n", filled.how.c_str());
  EXPECT_NE(filled.how.find("standstill before the start"), std::string::npos) << filled.how;
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(filled.options.vrw_mps_per_sqrt_s(k) / datasheet.vrw_mps_per_sqrt_s(k), 10.0, 1.5) << k;
    EXPECT_EQ(filled.options.arw_rad_per_sqrt_s(k), datasheet.arw_rad_per_sqrt_s(k)) << k;
  }
  EXPECT_NEAR(filled.floor.gyro, 100.0, 20.0) << "(10x)^2 on the datasheet's ARW";
  EXPECT_NEAR(filled.floor.accel, 1.0, 0.15) << "measured against itself";

  // Against the truth: as consistent as a live run configured with the installed noise (10x the datasheet's on
  // both, as simulated); with the measurement off and the 0 kept, overconfident in velocity.
  FilterOptions installed = datasheet, kept = no_vrw;
  installed.arw_rad_per_sqrt_s *= 10.0;
  installed.vrw_mps_per_sqrt_s *= 10.0;
  kept.installed_noise_floor = false;
  const NoiseFloorLiveRun right = run_live_noise_floor(sim, installed), zero = run_live_noise_floor(sim, kept);
  std::printf("live velocity NEES per dof: measured %.2f, as installed %.2f, VRW 0 kept %.2f\n",
              filled.vel_nees_per_dof, right.vel_nees_per_dof, zero.vel_nees_per_dof);
  std::printf("re-synchronisations: measured %ld, as installed %ld, VRW 0 kept %ld\n", filled.faults.gate_resyncs,
              right.faults.gate_resyncs, zero.faults.gate_resyncs);
  EXPECT_NEAR(filled.vel_nees_per_dof / right.vel_nees_per_dof, 1.0, 0.25);
  // Overconfident, the 0 kept lets the fixes leave the state, which must be re-synchronised. Its NEES over the
  // whole run no longer shows it: 6.9 before the re-synchronisation reopened the accelerometer biases and the
  // heading, 4.3 since (as installed 4.2).
  EXPECT_EQ(filled.faults.gate_resyncs, 0);
  EXPECT_EQ(right.faults.gate_resyncs, 0);
  EXPECT_GE(zero.faults.gate_resyncs, 1);
}

// Issue 48, item 2: the noise comes from where the vehicle stood, not from where the GNSS stood still. A car that
// turns 90 deg on the spot in the middle of a 34 s standstill (the GNSS does not move) under 3x vibration: the
// periodogram's median passes the turn by (9.3x against 9.4x without the turn, 9x simulated).
TEST(InstalledImuNoise, GivenATurnOnTheSpotInsideTheStandstill_ThenTheMeasuredNoiseIsTheVibrationsStill) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "ldv_test_noise_turn_on_the_spot";
  std::filesystem::create_directories(dir);
  const std::string scenario = (dir / "spot.yaml").string();
  std::ofstream(scenario) << "name: spot\n"
                             "start: {lat_deg: 30.5, lon_deg: 114.4, h_m: 20, yaw_deg: 40}\n"
                             "segments:\n"
                             "  - {type: static, duration_s: 15}\n"
                             "  - {type: turn, angle_deg: 90, duration_s: 4}\n"
                             "  - {type: static, duration_s: 15}\n"
                             "  - {type: accelerate, to_speed_mps: 10, duration_s: 8}\n"
                             "  - {type: straight, duration_s: 30}\n";
  sim::SimRequest req;
  req.grade = "3dm-gx2-typical";
  req.scenario = scenario;
  req.duration_s = 70.0;
  req.gnss_rate_hz = 5.0;
  req.seed = 3;
  req.vehicle.vibration_factor = 3.0;  // white noise 3x the grade's: PSD 9x
  req.vehicle.engine_accel_mps2 = 0.0;
  req.vehicle.engine_gyro_dps = 0.0;
  const sim::SimResult sim = sim::simulate(req);
  const FilterOptions datasheet = options_from_kfgins(sim.kfgins);
  const InstalledImuNoise noise = measure_installed_imu_noise(sim.imu, sim.gnss);
  ASSERT_TRUE(noise.found);
  EXPECT_GT(noise.standstill_s, 30.0) << "the turn is inside the GNSS standstill";
  const ImuNoiseScale psd = noise.psd_scale(datasheet.arw_rad_per_sqrt_s, datasheet.vrw_mps_per_sqrt_s);
  const ImuNoiseScale sigma = noise.psd_scale_sigma(datasheet.arw_rad_per_sqrt_s, datasheet.vrw_mps_per_sqrt_s);
  std::printf("[ info ] over %.0f s with a 90 deg turn: gyro %.2f +- %.2f, accel %.2f +- %.2f (simulated 9)\n",
              noise.standstill_s, psd.gyro, sigma.gyro, psd.accel, sigma.accel);
  EXPECT_NEAR(psd.gyro, 9.0, 3.0 * sigma.gyro);
  EXPECT_NEAR(psd.accel, 9.0, 3.0 * sigma.accel);
}

}  // namespace
}  // namespace ldv::est
