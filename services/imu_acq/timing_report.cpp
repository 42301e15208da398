#include "services/imu_acq/timing_report.hpp"

#include <algorithm>
#include <cmath>

namespace ldv::imu {

TimingReport::TimingReport(double nominal_interval_s, double bin_width_s)
    : lo_s_(nominal_interval_s - kBins / 2 * bin_width_s), bin_s_(bin_width_s) {}

void TimingReport::add_locked_stamp(const GpsTime& t) {
  if (last_) {
    // Week and seconds apart keep the difference's sub-nanosecond resolution.
    const double dt_s = (t.week - last_->week) * kSecondsPerWeek + (t.sow_s - last_->sow_s);
    ++n_;
    const double d = dt_s - mean_s_;
    mean_s_ += d / static_cast<double>(n_);
    m2_ += d * (dt_s - mean_s_);
    // The outer bins also collect everything beyond them, so no interval goes uncounted.
    const int bin = std::clamp(static_cast<int>(std::floor((dt_s - lo_s_) / bin_s_)), 0, kBins - 1);
    ++bins_[static_cast<std::size_t>(bin)];
  }
  last_ = t;
}

double TimingReport::std_s() const { return n_ > 1 ? std::sqrt(m2_ / static_cast<double>(n_ - 1)) : 0.0; }

ldv_lcm::imu_timing_t TimingReport::message(std::int64_t seq, double host_time_s, const timing::PpsTimeFit& fit,
                                            std::int64_t extra_missing_pps) const {
  ldv_lcm::imu_timing_t m{};
  m.seq = seq;
  m.host_time_s = host_time_s;
  m.interval_mean_s = mean_s_;
  m.interval_std_s = std_s();
  m.clock_drift_ppm = fit.locked() ? fit.frequency_offset_ppm() : 0.0;
  m.fit_residual_rms_s = fit.residual_rms_s();
  const auto& c = fit.counters();
  m.missing_pps = static_cast<int32_t>(c.missing + static_cast<std::uint64_t>(extra_missing_pps));
  m.late_pps = static_cast<int32_t>(c.late + c.spurious);
  m.hist_lo_s = lo_s_;
  m.hist_bin_s = bin_s_;
  std::copy(bins_.begin(), bins_.end(), m.hist_count);
  return m;
}

}  // namespace ldv::imu
