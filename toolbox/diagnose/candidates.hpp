#pragma once
// The candidates of the screening: every vocabulary effect (docs/effects.md) that the model under test
// does not estimate, tested as a constant parameter. Each candidate is the registry's own effect block,
// so its Jacobians (how it drives the navigation error, how it enters a measurement) are the filter's
// and the simulator's definitions, sign for sign.
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "estimator/effects/effect.hpp"
#include "estimator/options.hpp"

namespace ldv::diag {

struct Candidate {
  std::string name;
  std::unique_ptr<est::Effect> effect;
  int dim = 0;
  int column = 0;  // first column of this candidate in the joint sensitivity matrix
  std::vector<std::string> state_names;
  est::PrintUnit unit;
  Eigen::VectorXd assumed_si;    // value the model under test uses (configured lever arm / time offset, else 0)
  Eigen::VectorXd plausible_si;  // largest plausible size per state: below it a detectable size means "testable"
  std::string excitation;        // the manoeuvres that make it visible
};

// An effect of the vocabulary that is not screened, and why.
struct NotScreened {
  std::string name;
  std::string reason;
};

struct CandidateSet {
  std::vector<Candidate> candidates;
  int columns = 0;  // total parameters
  std::vector<NotScreened> not_screened;
};

// Candidates for a model: the screenable vocabulary minus the model's own effect names.
CandidateSet make_candidates(const est::FilterOptions& options, const std::vector<std::string>& model_effects);

// The options block that configures effect `name` when it is added to a model (nullptr for time_offset,
// which has scalar options).
est::BlockOptions* block_options(est::FilterOptions& options, const std::string& name);

// Sets the prior of an added effect: mean = value, 1-sigma = std (per state, SI).
void set_prior(est::FilterOptions& options, const std::string& name, const Eigen::VectorXd& value_si,
               const Eigen::VectorXd& std_si);

}  // namespace ldv::diag
