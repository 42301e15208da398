#pragma once
// A navigation solution as a time series that can be read at any instant: what `ldv compare` matches
// and what outage drifts are measured against (truth.nav, an uncut solution, a KF-GINS .nav).
#include <cmath>
#include <optional>
#include <vector>

#include "common/formats/nav_types.hpp"
#include "estimator/ins/nav_state.hpp"

namespace ldv::assess {

struct NavSample {
  double t_s = 0.0;  // GPS seconds of week (of NavSeries::week(); beyond 604800 s after a week rollover)
  Geodetic pos;
  Vec3 vel_n_mps = Vec3::Zero();
  Quat q_b_n = Quat::Identity();
};

// A filter state as a sample of its solution.
inline NavSample sample_of(const est::NavState& s) { return {s.t_s, s.pos, s.v_n_mps, s.q_b_n}; }

class NavSeries {
 public:
  NavSeries() = default;
  explicit NavSeries(std::vector<NavSample> samples);  // sorted by time (throws std::invalid_argument if not)
  // Times continue across a week rollover: t_s = (week - first week) * 604800 + sow, week() = the first week.
  static NavSeries from_records(const std::vector<NavRecord>& records);
  int week() const { return week_; }  // GPS week of t_s = 0 (-1: not known, e.g. built from samples)
  int last_week() const { return week_ < 0 ? -1 : week_ + static_cast<int>(std::floor(t_end_s() / kSecondsPerWeek)); }
  static constexpr double kSecondsPerWeek = 604800.0;

  bool empty() const { return samples_.empty(); }
  size_t size() const { return samples_.size(); }
  const std::vector<NavSample>& samples() const { return samples_; }
  double t_begin_s() const { return samples_.front().t_s; }
  double t_end_s() const { return samples_.back().t_s; }

  // Linear in position and velocity, slerp in attitude; nullopt outside the series or across a gap
  // longer than max_gap_s (no invention of data where there is none).
  std::optional<NavSample> at(double t_s, double max_gap_s = 1.5) const;

 private:
  std::vector<NavSample> samples_;
  int week_ = -1;
};

}  // namespace ldv::assess
