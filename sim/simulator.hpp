#pragma once
// `ldv sim` as a library: a scenario, an IMU grade and a list of effects in; exact truth, IMU
// increments, GNSS solutions and a matching KF-GINS configuration out. See sim/README.md.
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "common/formats/kfgins_config.hpp"
#include "common/formats/nav_types.hpp"
#include "common/formats/odometer_text.hpp"
#include "sim/gnss_model.hpp"
#include "sim/imu_error_model.hpp"
#include "sim/imu_grade.hpp"
#include "sim/motion_profile.hpp"
#include "sim/road_shocks.hpp"
#include "sim/truth_sample.hpp"
#include "sim/vehicle_realism.hpp"

namespace ldv::sim {

struct Outage {
  double start_s;   // relative to the run start
  double length_s;
};

struct SimRequest {
  std::string grade = "perfect";  // sim::imu_grade_names() or a grade YAML file
  uint64_t seed = 1;
  double duration_s = 600.0;
  std::string scenario = "figure8";  // a built-in name or a YAML file path
  double imu_rate_hz = 200.0;
  double gnss_rate_hz = 1.0;
  // Effect names (docs/effects.md), optionally NAME=v1,v2,v3 in engineering units (sim/README.md);
  // hidden unless declared.
  std::vector<std::string> effects;
  // Effects also written into the output config (injected with their default size when not in `effects`).
  std::vector<std::string> declared_effects;
  std::vector<Outage> outages;
  int gps_week = 2300;
  double start_sow_s = 345600.0;
  // false: no random noise anywhere (IMU white / Gauss-Markov / random walk / quantisation, GNSS noise,
  // latency jitter); deterministic errors (turn-on bias and scale drawn from the grade, ramps, every
  // injected effect, gravity anomaly) stay.
  bool with_noise = true;

  // Additions beyond the shared contract.
  std::string gnss_mode = "fixed";  // fixed | float | single
  bool gnss_velocity = false;       // 13-column gnss.txt and velocity in the RTKLIB .pos
  double gnss_latency_s = 0.08;     // mean solution latency (uniform jitter +-10 ms)
  std::optional<ImuGrade> custom_grade;  // overrides `grade` (tests: one noise term alone)
  double oscillator_hz = 10e6;      // time-stamp unit counter (imu_device.bin)
  double oscillator_ppm = 25.0;     // its frequency error
  int leap_seconds = 18;            // GPS - UTC, for NMEA times
  VehicleOptions vehicle;           // --realism and the vehicle effects (sim/vehicle_realism.hpp)
};

struct SimResult {
  SimRequest request;
  std::vector<TruthSample> truth;   // at every IMU epoch (t_s of the IMU sample), plus t0
  std::vector<ImuIncrement> imu;    // increments over (t - dt, t]
  std::vector<GnssFix> gnss;        // at the antenna, with lever arm, noise, outages, time offset
  std::vector<double> gnss_latency_s;  // per fix: available at t_s + latency
  KfGinsConfig kfgins;              // initial state from truth, noise from the grade; paths set by write_outputs
  // True values (SI) of every injected effect, by effect name; Gauss-Markov effects also carry
  // "NAME.sigma" and "NAME.tau_s"; grade draws (turn-on bias, scale) are included in gyro_bias etc.
  std::map<std::string, std::vector<double>> injected_effects;
  std::vector<std::string> declared_effects;
  std::vector<ImuBiasSample> imu_bias_history;  // 1 Hz: total true bias (constant + moving parts)
  std::string grade_source;
  std::string scenario_name;
  VehicleRealism realism;                  // the vehicle effects as simulated (preset draws resolved)
  std::vector<OdometerSample> odometer;    // odo.txt (empty without the odometer)
  std::vector<ShockEvent> shocks;          // road bumps (run time)
  std::vector<GnssOutlier> gnss_outliers;  // position jumps
};

SimResult simulate(const SimRequest& req, const std::function<void(double fraction)>& progress = {});

// Writes imu.txt gnss.txt truth.nav kfgins.yaml truth_effects.yaml truth_errors.txt gnss.pos
// imu_device.bin gnss.nmea (odo.txt with the odometer, datasheet.yaml with --realism vehicle) into out_dir,
// all-or-nothing (a temporary directory beside it, then moved). Sets result.kfgins paths (absolute, into out_dir).
void write_outputs(SimResult& result, const std::string& out_dir);

}  // namespace ldv::sim
