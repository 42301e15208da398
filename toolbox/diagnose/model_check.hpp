#pragma once
// Model check: are the innovations what the model says they are? NIS per sensor and axis against
// chi-square bands (with an effective sample size, since the innovations are correlated), whiteness
// (autocorrelation, Ljung-Box), gate rejections, and the same per manoeuvre segment.
#include <array>
#include <string>
#include <vector>

#include "toolbox/diagnose/filter_run.hpp"
#include "toolbox/diagnose/segments.hpp"

namespace ldv::diag {

struct Band {
  double value = 0.0, lo = 0.0, hi = 0.0;
  bool ok() const { return value >= lo && value <= hi; }
};

struct SegmentCheck {
  Segment segment = Segment::kStraight;
  int count = 0;
  Band mean_nis;          // 3-dof NIS, band from the segment's effective sample size
  Eigen::VectorXd rms;    // innovation RMS per row (GNSS: N E D) [m, m/s or rad/s]
  int rejected = 0;
};

struct SensorCheck {
  est::SensorName sensor = est::sensors::kGnssPosition;
  int count = 0, rejected = 0;
  Band mean_nis;               // E[NIS] = the measurement's rows
  std::vector<Band> axis_nis;  // per row: E[nu_i^2 / S_ii] = 1
  Eigen::VectorXd rms;
  std::vector<double> autocorrelation;  // of the normalised innovations (mean over axes), lags 0..
  double ljung_box = 0.0, ljung_box_p = 1.0;
  int ljung_box_lags = 0;
  double correlation_time = 1.0;   // integrated autocorrelation time [records]
  double effective_n = 0.0;        // count / correlation_time
  double long_run_factor = 1.0;    // long-run variance of the normalised innovations over their variance
  std::vector<SegmentCheck> segments;
  // NIS above its band: the model under-predicts its errors (something is missing). Below: the
  // model is pessimistic (noise larger than needed), which hides nothing.
  bool optimistic() const { return mean_nis.value > mean_nis.hi; }
  bool pessimistic() const { return mean_nis.value < mean_nis.lo; }
  bool gate_drops_fixes() const;  // more than 1 % of the measurements (at least 2) rejected at the gate
  bool ok() const;                // not optimistic and the gate drops no more than that
};

struct ModelCheck {
  std::vector<SensorCheck> sensors;
  double loglik = 0.0;  // log_likelihood of the run's measurements at its gate
  double measurement_interval_s = 1.0;
  bool consistent() const;
  bool gate_drops_fixes() const;  // for any sensor
  const SensorCheck* find(est::SensorName k) const;
};

ModelCheck check_model(const FilterRun& run, const std::vector<Segment>& epoch_labels, double confidence = 0.95);

// Sum over the measurements of -0.5 (log det S + min(nu^T S^-1 nu, gate)), the gate being the chi-square
// quantile of gate_probability for the measurement's rows. Capped as the model check caps its NIS: one
// 2 m RTK outlier (NIS ~10^4) would otherwise outweigh a whole drive's evidence and decide which model
// "fits" by how tight its S is at that one fix.
double log_likelihood(const std::vector<SensitivityRecord>& records, double gate_probability);
// One measurement's term of it (0 where S is not positive definite).
double log_likelihood_term(const SensitivityRecord& record, double gate_probability);

}  // namespace ldv::diag
