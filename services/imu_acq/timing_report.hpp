#pragma once
// The 1 Hz IMU_TIMING message: interval statistics of the PPS-disciplined stamps (the paper's
// "0.0100005 s +- 9.45 us"), the oscillator's rate error, the fit residual, missing and late PPS,
// and a 32-bin histogram of the sample interval centred on the nominal interval. Only intervals
// between consecutive fitted stamps count (a sample lost on the link is not a timing error).
#include <array>
#include <cstdint>

#include <ldv_lcm/imu_timing_t.hpp>

#include "services/imu_acq/timing/pps_time_fit.hpp"
#include <optional>

#include "common/time/gps_time.hpp"

namespace ldv::imu {

class TimingReport {
 public:
  static constexpr int kBins = 32;
  TimingReport(double nominal_interval_s, double bin_width_s);

  // A stamp from the fit (extrapolated stamps are left out: they would measure the fallback).
  void add_locked_stamp(const GpsTime& t);
  // A flagged stamp breaks the chain of consecutive fitted stamps.
  void break_chain() { last_.reset(); }

  ldv_lcm::imu_timing_t message(std::int64_t seq, double host_time_s, const timing::PpsTimeFit& fit,
                                std::int64_t extra_missing_pps) const;
  std::uint64_t intervals() const { return n_; }
  double mean_s() const { return mean_s_; }
  double std_s() const;

 private:
  std::uint64_t n_ = 0;
  double mean_s_ = 0.0, m2_ = 0.0;  // Welford
  double lo_s_, bin_s_;
  std::array<std::int32_t, kBins> bins_{};
  std::optional<GpsTime> last_;
};

}  // namespace ldv::imu
