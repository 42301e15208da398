#pragma once
// The timing statistics the paper reports for its time-stamp unit ("0.0100005 s +- 9.45 us between
// samples over 14 h"): mean and standard deviation of the interval between consecutive sample
// stamps, min/max, a histogram around the nominal interval, and gaps (missing samples).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/time/gps_time.hpp"

namespace ldv::timing {

struct IntervalHistogram {
  double first_edge_s = 0.0;  // lower edge of bin 0
  double bin_width_s = 0.0;
  std::vector<std::uint64_t> bins;
  std::uint64_t below = 0, above = 0;  // outside the binned range
};

class SampleIntervalStatistics {
 public:
  // Bins of bin_width_s centred on nominal_interval_s, half_bins on each side of the centre bin.
  explicit SampleIntervalStatistics(double nominal_interval_s, double bin_width_s = 1e-6, int half_bins = 50);

  void add_stamp(const GpsTime& t);

  std::uint64_t intervals() const { return n_; }
  double mean_s() const { return mean_s_; }
  double std_s() const;
  double min_s() const { return min_s_; }
  double max_s() const { return max_s_; }
  // Intervals longer than 1.5 nominal, and the samples they lost.
  std::uint64_t gaps() const { return gaps_; }
  std::uint64_t missing_samples() const { return missing_samples_; }
  const IntervalHistogram& histogram() const { return histogram_; }
  // "interval 0.0100005 s +- 9.45 us (n=..., min ..., max ..., gaps ...)"
  std::string summary() const;

 private:
  double nominal_s_;
  std::optional<GpsTime> last_;
  std::uint64_t n_ = 0;
  double mean_s_ = 0.0, m2_ = 0.0;  // Welford
  double min_s_ = 0.0, max_s_ = 0.0;
  std::uint64_t gaps_ = 0, missing_samples_ = 0;
  IntervalHistogram histogram_;
};

}  // namespace ldv::timing
