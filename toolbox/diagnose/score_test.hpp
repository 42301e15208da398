#pragma once
// Screening: a score (Lagrange multiplier) test of every candidate from the one screening run.
//   u_k = s_k^T S_k^-1 nu_k      score contribution of measurement epoch k
//   g = sum u_k,  J = sum s_k^T S_k^-1 s_k,  e_hat = J^-1 g   (e = assumed - true)
// The innovations of a real filter are neither white nor exactly of covariance S (coloured GNSS
// noise, approximate process noise), so the statistic uses the long-run (Newey-West, Bartlett) variance
// V of the score contributions instead of J, and the Hotelling T^2 tail with the equivalent degrees of
// freedom of V (1.5 N / bandwidth): T = g^T V^-1 g.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "toolbox/diagnose/candidates.hpp"
#include "toolbox/diagnose/segments.hpp"
#include "toolbox/diagnose/sensitivity_observer.hpp"

namespace ldv::diag {

struct ScreeningOptions {
  double alpha = 0.05;          // family-wise false-alarm rate of the screening (Bonferroni over candidates)
  double power = 0.8;           // for the minimal detectable size
  double group_correlation = 0.9;
  double bandwidth_s = 120.0;   // Newey-West bandwidth (>> correlation time of the GNSS errors)
  double statistic_scale = 1.0; // calibration: T is divided by it (found on runs without hidden effects)
};

struct CandidateScore {
  std::string name;
  int dim = 0;
  std::vector<std::string> state_names;
  est::PrintUnit unit;
  std::vector<int> tested;       // components with enough information on this drive
  bool testable = false;
  double statistic = 0.0;        // robust T (after statistic_scale)
  double statistic_model = 0.0;  // g^T J^-1 g (white innovations of covariance S assumed)
  double p_value = 1.0;          // Hotelling tail of `statistic`
  double rank_z = -1e300;        // Wilson-Hilferty z of the statistic: ranking across dimensions
  bool significant = false;      // p below alpha / (number of testable candidates)
  Eigen::VectorXd estimate_si;   // true value implied: assumed - e_hat (NaN when not tested)
  Eigen::VectorXd sigma_si;      // robust 1-sigma
  Eigen::VectorXd mds_si;        // minimal detectable size (alpha, power), per component (inf if untestable)
  std::vector<std::string> group;  // candidates this drive cannot tell apart from it (itself included)
  std::string separate_by;         // the manoeuvre that would separate the group
};

struct ScreeningResult {
  std::vector<CandidateScore> ranked;  // best first; untestable last
  std::vector<std::string> candidate_names;          // in column order of `correlation`
  Eigen::MatrixXd correlation;         // largest canonical correlation between candidates' sensitivities
  double nu_eff = 0.0;                 // equivalent dof of the long-run variance
  int bandwidth_epochs = 0, epochs = 0, testable = 0;
  double threshold_p = 0.0;            // alpha / testable
};

ScreeningResult screen(const CandidateSet& set, const std::vector<SensitivityRecord>& records,
                       const std::vector<Segment>& record_segments, const ScreeningOptions& opt);

}  // namespace ldv::diag
