#pragma once
// `ldv diagnose` as a library (DESIGN.md section 3): run the model, check it, screen every missing
// effect, confirm the best by rerunning with it, stepwise; then the verdict and the rerun with it.
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "estimator/filter/imu_noise_scale.hpp"
#include "estimator/filter/noise_adaptation.hpp"
#include "toolbox/diagnose/confirmation.hpp"
#include "toolbox/diagnose/model_check.hpp"
#include "toolbox/diagnose/score_test.hpp"
#include "toolbox/diagnose/truth_error.hpp"

namespace ldv::diag {

struct DiagnoseOptions {
  est::FilterOptions model;      // the model under test
  ScreeningOptions screening;
  int max_added = 3;             // stepwise: at most this many effects added
  // Significant candidates rerun per step, best first; -1: every one. The likelihood of the reruns decides among
  // them: the screening's order can be wrong where effects look alike (a MEMS accel misalignment of 6-7 mrad ranked
  // fifth behind a gyro misalignment, its rerun gains the most).
  int max_confirmed_per_step = -1;
  // Where the gate rejects more than 1 % of a sensor's measurements, every testable candidate is rerun too
  // (diagnosis.cpp: so far from the data the score test loses its power).
  bool confirm_all_when_gate_rejects = true;
  double truth_skip_s = 60.0;    // initial convergence left out of the error against truth
  // A model far from the data rejects most measurements and diverges: then the diagnosis runs with
  // the gate opened (every measurement used), so the innovations still carry the missing effect.
  double open_gate_above_rejected = 0.2;
  // The IMU noise as installed, measured over a GNSS standstill in the data (est::measure_installed_imu_noise);
  // above kApplyImuNoiseScale times the configured PSD the diagnosis runs with it (its first step). A vehicle's
  // vibration puts it 10-300x the datasheet's PSD, and a model that far off the data hides the effects it
  // is tested for. The diagnosis's own runs never adapt their noise.
  bool measure_imu_noise = true;
  bool verbose = false;          // progress on stderr
};

// What the system estimated on its own, outside the model under test (issue 36: "self-calibration reports what
// it found"): the IMU latency taken out of the stamps, the installed IMU noise, the turn-on gyro bias the start
// took out. A finding, with its value and sigma, whether or not it was applied: a residual it cleaned is not
// evidence that the model is consistent.
struct SelfCalibration {
  std::string name;                        // effect vocabulary (docs/effects.md): time_offset, imu_noise, gyro_bias
  Eigen::VectorXd estimate_si, sigma_si;   // SI (imu_noise: PSD factors); sigma NaN where none is known
  std::string unit;                        // how the text report prints it (ms, x, deg/h)
  double print_scale = 1.0;                // SI -> unit
  bool applied = false;
  std::string note;                        // what it is and what was done with it, in words
};

// One stepwise round: the model as it was, what the screening found, what the reruns said.
struct DiagnosisStep {
  std::vector<std::string> model_effects;
  CandidateSet candidates;
  ModelCheck check;
  ScreeningResult screening;
  std::vector<Confirmation> confirmations;
  std::string added;  // empty: the stepwise search stopped here
};

struct Diagnosis {
  std::string model;                 // name of the model under test
  std::vector<std::string> model_effects;
  std::vector<DiagnosisStep> steps;  // steps[0] is the model under test
  // The model's missing effects, best first: those the first step confirmed (reran) by penalised likelihood
  // gain, accepted before rejected; then the rest by screening statistic. The score test ranks by a linear
  // look at the innovations; a rerun with the effect added is the better judge where two candidates are close.
  std::vector<CandidateScore> ranking;
  std::vector<std::string> add;      // the verdict
  std::vector<EffectEstimate> added_estimates;  // their estimates in the final rerun
  est::FilterOptions final_options;
  FilterRun before, after;           // after == before when nothing is added
  std::vector<Segment> labels_before, labels_after;
  ModelCheck check_after;
  TruthError truth_before, truth_after;
  double cpu_s = 0.0;
  int filter_runs = 0;
  bool gate_opened = false;          // the model rejected too many measurements: diagnosed without gate
  // The configured IMU white-noise PSDs times these (gyro, accel) are what the data say (1: not measured or
  // not above the configuration); when applied, configured_check is the model check with the configured noise.
  est::ImuNoiseScale imu_noise_scale;
  // The factors as measured (below 1 too: a datasheet that overstates the noise) and their 1-sigma (NaN: none).
  est::ImuNoiseScale imu_noise_measured{NAN, NAN}, imu_noise_measured_sigma{NAN, NAN};
  double imu_noise_standstill_s = 0.0;  // the standstill it was measured over (0: none found)
  // The factors the GNSS position innovations call for on the stated variance, per solution quality, estimated apart
  // from the IMU's (FilterOptions::split_noise_adaptation, a pass of its own on the model under test): the adaptation
  // as that pass ended (a class with no fixes was not seen). Applied only where a step took it in (below).
  est::NoiseAdaptation gnss_noise;
  // The GNSS noise a step added, if one did (noise_candidate.hpp): the stated variance of the classes it lists times
  // its factors (final_options.gnss_variance_scale, ldv.gnss_variance_scale in the tuned configuration).
  std::optional<EffectEstimate> gnss_noise_added;
  // The IMU white noise a step raised, if one did: the PSDs times these [gyro, accel] (final_options).
  std::optional<EffectEstimate> imu_noise_added;
  bool imu_noise_applied = false;
  ModelCheck configured_check;
  // Every self-calibration finding (diagnose() adds the noise and the turn-on bias; `ldv diagnose` adds what the
  // input loading estimated, e.g. the IMU latency).
  std::vector<SelfCalibration> self_calibration;
  bool self_calibration_applied() const;
  bool consistent() const;  // the final model passes its check and the last step adds nothing
  bool changed() const { return !add.empty() || gnss_noise_added || imu_noise_added; }  // an effect or a noise
};

// Above this factor on the configured PSD the measured IMU noise replaces the configured one.
inline constexpr double kApplyImuNoiseScale = 2.0;

Diagnosis diagnose(const DiagnoseInputs& in, const DiagnoseOptions& opt);

// The KF-GINS YAML snippet that adds the verdict: `ldv: add: [...]` and the estimated priors.
std::string config_snippet(const Diagnosis& d);

}  // namespace ldv::diag
