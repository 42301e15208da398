#pragma once
// Manoeuvre segments from the filter's own motion (no truth needed): where does the model fail?
#include <string>
#include <vector>

#include "toolbox/diagnose/filter_run.hpp"

namespace ldv::diag {

enum class Segment { kStatic, kStraight, kTurning, kAccelerating, kOutage };
constexpr int kSegmentCount = 5;
const char* segment_name(Segment s);

struct SegmentThresholds {
  double static_speed_mps = 0.2;
  double static_rate_rad_s = 1.0 * 3.141592653589793 / 180.0;
  double turn_rate_rad_s = 3.0 * 3.141592653589793 / 180.0;  // yaw rate about the local vertical
  double accel_mps2 = 0.4;                                   // horizontal acceleration
};

// One label per epoch: outage, then static, turning, accelerating, else straight.
std::vector<Segment> classify_epochs(const std::vector<EpochSample>& epochs, const SegmentThresholds& th = {});
// The label of the epoch at or just before t (epochs sorted by time).
Segment segment_at(const std::vector<EpochSample>& epochs, const std::vector<Segment>& labels, double t_s);
// Yaw rate about the local down axis [rad/s].
double yaw_rate_rad_s(const EpochSample& e);

}  // namespace ldv::diag
