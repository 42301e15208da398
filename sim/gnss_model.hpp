#pragma once
// GNSS solutions at the antenna: truth position (lever arm applied, taken at the epoch it is labelled with:
// GPS time; a time_offset is put on the IMU's tags) plus white and Gauss-Markov (coloured) noise per NED axis at the
// level of the solution type, scheduled outages and a reporting latency.
#include <string>
#include <vector>

#include "common/formats/nav_types.hpp"
#include "sim/motion_profile.hpp"
#include "sim/truth_sample.hpp"

namespace ldv::sim {

struct GnssErrorLevel {
  GnssQuality quality = GnssQuality::kFixed;
  Vec3 white_std_ned_m = Vec3::Zero();
  Vec3 colored_std_ned_m = Vec3::Zero();  // Gauss-Markov, stationary sigma
  double colored_tau_s = 60.0;
  Vec3 vel_std_n_mps = Vec3::Zero();      // white
  int num_sats = 0;
  double ratio = 0.0;  // ambiguity validation ratio (RTKLIB)
  double age_s = 0.0;  // age of differential corrections
};
// mode: fixed | float | single. Throws InputError for other names.
GnssErrorLevel gnss_error_level(const std::string& mode);

struct GnssSchedule {
  double rate_hz = 1.0;
  struct Window {
    double start_s, length_s;
  };
  std::vector<Window> outages;  // run time
  Vec3 lever_arm_b_m = Vec3::Zero();
  double latency_mean_s = 0.08, latency_jitter_s = 0.01;  // solution available after its epoch
  bool with_velocity = false;
  bool with_noise = true;
  double velocity_lag_s = 0.0;         // the velocity is the antenna's at (measurement time - lag)
  double velocity_noise_factor = 1.0;  // simulated velocity noise = factor x the stated std
  double outlier_rate = 0.0;           // fraction of epochs with a 1-3 m jump (stream "gnss_outliers")
};

// A single-epoch position jump (quality and stated std unchanged).
struct GnssOutlier {
  double t_s = 0.0;  // GPS seconds of week of the fix
  Vec3 offset_ned_m = Vec3::Zero();
};

struct GnssRun {
  std::vector<GnssFix> fixes;
  std::vector<double> latency_s;  // per fix: arrival time = t_s + latency
  std::vector<GnssOutlier> outliers;
};

// Antenna position and velocity at run time t (between IMU epochs: Hermite interpolation of the
// truth positions; attitude and velocity in closed form from the profile).
struct AntennaTruth {
  Geodetic pos;
  Vec3 vel_n_mps;
};
AntennaTruth antenna_truth_at(const MotionProfile& m, const std::vector<TruthSample>& truth, double dt_s, double t_s,
                              const Vec3& lever_arm_b_m);

GnssRun simulate_gnss(const MotionProfile& m, const std::vector<TruthSample>& truth, double dt_s,
                      const GnssErrorLevel& level, const GnssSchedule& schedule, uint64_t seed);

}  // namespace ldv::sim
