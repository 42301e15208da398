#include "toolbox/diagnose/segments.hpp"

#include <algorithm>

namespace ldv::diag {

const char* segment_name(Segment s) {
  switch (s) {
    case Segment::kStatic: return "static";
    case Segment::kStraight: return "straight";
    case Segment::kTurning: return "turning";
    case Segment::kAccelerating: return "accelerating";
    case Segment::kOutage: return "outage";
  }
  return "?";
}

double yaw_rate_rad_s(const EpochSample& e) {
  return (C_b_n_from_euler(e.rpy_rad) * e.omega_ib_b_rad_s).z();
}

std::vector<Segment> classify_epochs(const std::vector<EpochSample>& epochs, const SegmentThresholds& th) {
  std::vector<Segment> out;
  out.reserve(epochs.size());
  for (const EpochSample& e : epochs) {
    const double speed = e.v_n_mps.head<2>().norm();
    if (e.outage)
      out.push_back(Segment::kOutage);
    else if (speed < th.static_speed_mps && e.omega_ib_b_rad_s.norm() < th.static_rate_rad_s)
      out.push_back(Segment::kStatic);
    else if (std::abs(yaw_rate_rad_s(e)) > th.turn_rate_rad_s)
      out.push_back(Segment::kTurning);
    else if (e.a_n_mps2.head<2>().norm() > th.accel_mps2)
      out.push_back(Segment::kAccelerating);
    else
      out.push_back(Segment::kStraight);
  }
  return out;
}

Segment segment_at(const std::vector<EpochSample>& epochs, const std::vector<Segment>& labels, double t_s) {
  if (epochs.empty()) return Segment::kStraight;
  auto it = std::upper_bound(epochs.begin(), epochs.end(), t_s + 1e-6,
                             [](double t, const EpochSample& e) { return t < e.t_s; });
  const size_t i = it == epochs.begin() ? 0 : static_cast<size_t>(it - epochs.begin()) - 1;
  return labels[i];
}

}  // namespace ldv::diag
