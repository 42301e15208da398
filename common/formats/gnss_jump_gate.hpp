#pragma once
// Rejects GNSS position jumps: a solution more than max_jump_m from where the last two accepted
// solutions say the antenna should be (last position + velocity * dt; the velocity is the
// solution's own when it has one, else the difference of the last two). A low-dynamic vehicle
// cannot do that between epochs, so it is a wrong fix (e.g. a wrong integer ambiguity set), not a
// motion. If the receiver keeps reporting the new place (rejections_to_reset in a row), the jump
// was real (the gate's history was the wrong one) and the gate restarts on it. After a gap longer
// than max_gap_s there is nothing to predict from, so the gate restarts too.
#include <cstdint>
#include <deque>

#include "common/formats/gnss_solution.hpp"

namespace ldv::gnss {

struct JumpGateOptions {
  double max_jump_m = 30.0;
  double max_gap_s = 5.0;
  int rejections_to_reset = 5;
};

enum class JumpVerdict {
  kAccepted,
  kRestarted,     // accepted as the start of a new history (first, after a gap, or a real jump)
  kJumpRejected,  // too far from the prediction
  kTimeRejected,  // not after the last accepted epoch (a duplicate or time going backwards)
};

struct JumpGateCounters {
  std::uint64_t accepted = 0;
  std::uint64_t restarts = 0;
  std::uint64_t jumps_rejected = 0;
  std::uint64_t time_rejected = 0;
};

class JumpGate {
 public:
  explicit JumpGate(JumpGateOptions options = {}) : options_(options) {}

  JumpVerdict check(const GnssSolution& s);
  // Distance of the last checked solution from its prediction [m] (0 when nothing to predict from).
  double last_deviation_m() const { return last_deviation_m_; }
  const JumpGateCounters& counters() const { return counters_; }

 private:
  JumpVerdict restart(const GnssSolution& s);

  JumpGateOptions options_;
  JumpGateCounters counters_;
  std::deque<GnssSolution> history_;  // last accepted, newest at the back, at most 2
  int consecutive_rejections_ = 0;
  double last_deviation_m_ = 0.0;
};

}  // namespace ldv::gnss
