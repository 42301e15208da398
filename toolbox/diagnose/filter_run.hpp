#pragma once
// One run of the navigation filter over the inputs, keeping what the diagnosis looks at: the
// innovations (and, when screening, their sensitivities), the navigation state and the filter's own
// rate / specific force at 10 Hz (for the manoeuvre segments and the error against truth), and the
// final estimates of the model's effect blocks.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/formats/kfgins_config.hpp"
#include "common/formats/nav_types.hpp"
#include "estimator/run/run_navigation.hpp"
#include "toolbox/diagnose/sensitivity_observer.hpp"

namespace ldv::diag {

struct DiagnoseInputs {
  std::vector<ImuIncrement> imu;
  std::vector<GnssFix> gnss;
  KfGinsConfig cfg;
  std::vector<NavRecord> truth;  // optional (IMU centre, as truth.nav)
  std::vector<est::ObservationPtr> others;  // other sensors' readings (odometer), time order
};

struct EpochSample {
  double t_s = 0.0;
  Geodetic pos;
  Vec3 v_n_mps = Vec3::Zero();
  Vec3 rpy_rad = Vec3::Zero();
  Vec3 omega_ib_b_rad_s = Vec3::Zero();  // compensated, body
  Vec3 f_b_mps2 = Vec3::Zero();
  Vec3 a_n_mps2 = Vec3::Zero();
  bool outage = false;  // filter status: no accepted GNSS for > 2 s
};

struct EffectEstimate {
  std::string name;
  std::vector<std::string> state_names;
  est::PrintUnit unit;
  Eigen::VectorXd value_si, std_si;
};

struct FilterRun {
  std::vector<std::string> effects;  // the model's blocks, in order
  std::vector<SensitivityRecord> records;  // every measurement; `s` filled when screened
  std::vector<EpochSample> epochs;   // 10 Hz
  std::vector<EffectEstimate> estimates;
  est::RunSummary summary;
  double gate_probability = 0.9999;  // the run's chi-square gate (opened when the model rejected too much)
  double cpu_s = 0.0;
};

// Runs `options` over the inputs. With `candidates`, also carries their sensitivities (screening run).
FilterRun run_filter(const DiagnoseInputs& in, const est::FilterOptions& options,
                     const CandidateSet* candidates = nullptr);

// The process's CPU time so far: what a run and a diagnosis report as their cost.
double process_cpu_seconds();

}  // namespace ldv::diag
