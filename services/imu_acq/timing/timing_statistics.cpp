#include "services/imu_acq/timing/timing_statistics.hpp"

#include <cmath>
#include <cstdio>

namespace ldv::timing {

SampleIntervalStatistics::SampleIntervalStatistics(double nominal_interval_s, double bin_width_s, int half_bins)
    : nominal_s_(nominal_interval_s) {
  histogram_.bin_width_s = bin_width_s;
  histogram_.first_edge_s = nominal_interval_s - (half_bins + 0.5) * bin_width_s;
  histogram_.bins.assign(2 * half_bins + 1, 0);
}

void SampleIntervalStatistics::add_stamp(const GpsTime& t) {
  if (last_) {
    // Week and seconds apart, so the difference keeps its sub-nanosecond resolution.
    const double dt = (t.week - last_->week) * kSecondsPerWeek + (t.sow_s - last_->sow_s);
    if (dt > 1.5 * nominal_s_) {
      ++gaps_;
      missing_samples_ += static_cast<std::uint64_t>(std::llround(dt / nominal_s_) - 1);
    } else {
      ++n_;
      const double d = dt - mean_s_;
      mean_s_ += d / static_cast<double>(n_);
      m2_ += d * (dt - mean_s_);
      min_s_ = n_ == 1 ? dt : std::min(min_s_, dt);
      max_s_ = n_ == 1 ? dt : std::max(max_s_, dt);
      const double bin = std::floor((dt - histogram_.first_edge_s) / histogram_.bin_width_s);
      if (bin < 0) ++histogram_.below;
      else if (bin >= static_cast<double>(histogram_.bins.size())) ++histogram_.above;
      else ++histogram_.bins[static_cast<std::size_t>(bin)];
    }
  }
  last_ = t;
}

double SampleIntervalStatistics::std_s() const { return n_ > 1 ? std::sqrt(m2_ / static_cast<double>(n_ - 1)) : 0.0; }

std::string SampleIntervalStatistics::summary() const {
  char buf[256];
  std::snprintf(buf, sizeof buf, "interval %.7f s +- %.3f us (n=%llu, min %.7f s, max %.7f s, gaps %llu, missing %llu)",
                mean_s_, std_s() * 1e6, static_cast<unsigned long long>(n_), min_s_, max_s_,
                static_cast<unsigned long long>(gaps_), static_cast<unsigned long long>(missing_samples_));
  return buf;
}

}  // namespace ldv::timing
