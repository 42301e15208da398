#pragma once
// Offline runs of the filter over whole files: what `ldv nav` (and `ldv diagnose`, `ldv outage`) call.
#include <functional>
#include <string>
#include <vector>

#include "common/formats/kfgins_config.hpp"
#include "common/formats/nav_types.hpp"
#include "estimator/calibrate/imu_stamp_jitter.hpp"
#include "estimator/filter/records.hpp"
#include "estimator/filter/status.hpp"
#include "estimator/ins/alignment.hpp"
#include "estimator/run/nav_session.hpp"

namespace ldv::est {

// KF-GINS configuration -> filter options: imunoise (arw, vrw, gbstd, abstd, gsstd, asstd, corrtime),
// init biases/scales and their std, antlever; plus the optional `ldv:` section keys
//   model, add [list], drop [list], cov_period_s, gate_probability, use_gnss_velocity, zupt (bool),
//   history_s, gnss_bias_sigma_m (number or [N, E, D]), gnss_bias_tau_s, align_speed_mps,
//   align_hypotheses, and the land-vehicle aids: aids [nhc, zaru, odometer], vehicle_mounting_deg
//   [roll, pitch, yaw] (coarse IMU-in-vehicle rotation), nhc_std_mps, odometer_std_mps,
//   odometer_lever_arm_m [x, y, z] (body axes), odometer_scale. Throws InputError (file, key) on a wrong type.
FilterOptions options_from_kfgins(const KfGinsConfig& cfg);
// KF-GINS fix by fix (ldv.kfgins_compatible, --kfgins-compatible): its gate-free update of every fix, a fix within
// 1 ms of an IMU epoch applied there (TIME_ALIGN_ERR), the covariance propagated every sample (unless the
// configuration sets ldv.cov_period_s), no robust update and no noise adaptation.
void make_kfgins_compatible(FilterOptions& o, const KfGinsConfig& cfg);
// A number from the `ldv:` section, or `fallback` when absent; InputError (file, line, key) on a wrong type.
double ldv_number(const KfGinsConfig& cfg, const char* key, double fallback);

// The session a configuration describes: the filter options, the alignment (default:
// alignment_options_from(filter)), a given start (initpos/initvel/initatt, all three), starttime/endtime.
SessionOptions session_options_from(const KfGinsConfig& cfg, const FilterOptions& filter,
                                    const AlignmentOptions* alignment = nullptr);

// Whether the IMU latency is looked for in the data (offline over the file, imu_latency.hpp; live over a
// sliding window, imu_latency_window.hpp): `requested` (auto | off) when given, else the key ldv.imu_latency,
// else auto unless the user set the shift (`shift_given`: ldv.imu_time_shift_s, --imu-time-shift) or asked
// for KF-GINS's behaviour (no robust update). InputError (file, line) on another value.
bool imu_latency_wanted(const KfGinsConfig& cfg, const FilterOptions& filter, const std::string& requested,
                        bool shift_given);

struct RunCallbacks {
  std::function<void(const NavFilter&)> on_epoch;                       // after every IMU sample
  std::function<void(const InnovationRecord&)> on_innovation;           // every measurement decision
  std::function<void(double fraction_done)> on_progress;                // about every 2 %
};

struct RunSummary {
  long imu_samples = 0, gnss_fixes = 0, other_observations = 0;
  double t_start_s = 0.0, t_end_s = 0.0;  // the first and last solution epochs
  std::string initialisation;  // "given", or the alignment method
  Vec3 gyro_bias_seed_rad_s = Vec3::Zero();  // turn-on bias from the static start, taken out (alignment.hpp)
  Vec3 gyro_bias_seed_std_rad_s = Vec3::Zero();  // its 1-sigma (0: not measured, e.g. a warm start's saved bias)
  FaultCounters faults;
  std::uint32_t final_status = 0;
  // With FilterOptions::adapt_imu_noise: the factors on the configured IMU noise PSDs a standstill in the
  // data showed (the adaptation's floor), and the adapted factor on top of it at the end of the run.
  ImuNoiseScale imu_noise_floor;
  double imu_noise_standstill_s = 0.0;  // the standstill it was measured over (0: none in the data, floor 1)
  // A white-noise density configured as 0 that the standstill's measurement replaced (NavFilter::
  // fill_unset_white_noise), in words with the values; empty when none.
  std::string white_noise_filled;
  double imu_noise_scale_end = 1.0;
  // With FilterOptions::imu_stamp_jitter_from_tags: the IMU tags' scatter about the sensor's sampling, modelled.
  ImuStampJitter imu_stamp_jitter;
  std::optional<NavSession::BodyHeading> body_heading;  // NavSession::body_heading
};

// Runs the files through a NavSession (nav_session.hpp: the same session `ldv nav --lcm-log` and the fusion
// service drive) over [start_time, end_time] of the inputs (end < 0: to the end): the given state or the
// alignment, then each reading handed over NavSession::kLookahead_s before the IMU reaches it, so it is
// applied at its exact epoch. Offline only: the IMU noise as installed is measured over the file's longest
// standstill first (FilterOptions::adapt_imu_noise). Throws InputError if alignment never succeeds. `alignment`:
// settings of the alignment without a given state (default: alignment_options_from(filter.options())). `others`:
// readings of other sensors (odometer, ...) in time order, fed like the fixes.
RunSummary run_navigation(const std::vector<ImuIncrement>& imu, const std::vector<GnssFix>& gnss,
                          const KfGinsConfig& cfg, NavFilter& filter, const RunCallbacks& callbacks,
                          const AlignmentOptions* alignment = nullptr,
                          const std::vector<ObservationPtr>* others = nullptr);

// The epoch run_navigation() will start the filter at: the given state's, or where the alignment from the data
// succeeds (the same aligner, without its heading trials). Throws as run_navigation() does.
double initialisation_epoch(const std::vector<ImuIncrement>& imu, const std::vector<GnssFix>& gnss,
                            const KfGinsConfig& cfg, const AlignmentOptions& alignment);

}  // namespace ldv::est
