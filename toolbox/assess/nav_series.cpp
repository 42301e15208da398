#include "toolbox/assess/nav_series.hpp"

#include <algorithm>
#include <stdexcept>

namespace ldv::assess {

NavSeries::NavSeries(std::vector<NavSample> samples) : samples_(std::move(samples)) {
  for (size_t i = 1; i < samples_.size(); ++i)
    if (samples_[i].t_s < samples_[i - 1].t_s) throw std::invalid_argument("navigation series: time goes backwards");
}

NavSeries NavSeries::from_records(const std::vector<NavRecord>& records) {
  std::vector<NavSample> s;
  s.reserve(records.size());
  const int week0 = records.empty() ? 0 : records.front().week;
  for (const NavRecord& r : records)
    s.push_back({(r.week - week0) * kSecondsPerWeek + r.sow_s, r.pos, r.vel_n_mps, quat_from_euler(r.rpy_rad)});
  NavSeries series(std::move(s));
  series.week_ = records.empty() ? -1 : week0;
  return series;
}

std::optional<NavSample> NavSeries::at(double t_s, double max_gap_s) const {
  constexpr double kEdge_s = 1e-6;  // an epoch at the very end still counts
  if (samples_.empty() || t_s < samples_.front().t_s - kEdge_s || t_s > samples_.back().t_s + kEdge_s) return std::nullopt;
  auto hi = std::lower_bound(samples_.begin(), samples_.end(), t_s, [](const NavSample& s, double t) { return s.t_s < t; });
  if (hi == samples_.end()) return samples_.back();
  if (hi->t_s - t_s < kEdge_s || hi == samples_.begin()) return *hi;
  const NavSample& b = *hi;
  const NavSample& a = *(hi - 1);
  const double span = b.t_s - a.t_s;
  if (span > max_gap_s) return std::nullopt;
  const double w = (t_s - a.t_s) / span;
  NavSample out;
  out.t_s = t_s;
  out.pos.lat_rad = a.pos.lat_rad + w * (b.pos.lat_rad - a.pos.lat_rad);
  out.pos.lon_rad = a.pos.lon_rad + w * wrap_pi(b.pos.lon_rad - a.pos.lon_rad);
  out.pos.h_m = a.pos.h_m + w * (b.pos.h_m - a.pos.h_m);
  out.vel_n_mps = a.vel_n_mps + w * (b.vel_n_mps - a.vel_n_mps);
  out.q_b_n = a.q_b_n.slerp(w, b.q_b_n);
  return out;
}

}  // namespace ldv::assess
