#pragma once
// How far the IMU's time tags scatter about the instants the sensor sampled: a host that stamps each sample when it
// reads it (USB, serial, a driver's poll) tags it somewhere within its read interval, and a sensor read faster than
// it samples repeats a sample under a later tag (the real walk in ../shared: a 100 Hz sensor read at 150 Hz, 34 % of
// its rows repeats, tags 2.0 ms off a regular grid). Each increment then spans a wrong interval; the filter models
// the error (FilterOptions::imu_stamp_jitter_s). Measured from the tags alone: the first tag of each distinct sample
// against a regular grid fitted over windows of kWindowSamples samples (the grid's offset is latency, not jitter).
#include <vector>

#include "common/formats/nav_types.hpp"

namespace ldv::est {

struct ImuStampJitter {
  bool found = false;              // enough samples to tell
  double sigma_s = 0.0;            // the tags' scatter about the sampling grid (median over the windows)
  double sigma_sigma_s = 0.0;      // its 1-sigma (the windows' robust spread over sqrt(windows))
  double sample_interval_s = 0.0;  // the sensor's own sampling interval
  double repeated_fraction = 0.0;  // rows that repeat the sample before them exactly
  int windows = 0;
  static constexpr int kWindowSamples = 200;
  // Worth a word: above a thousandth of the interval (below, the increments' error is a millionth of the rate's
  // change: the tags are the sensor's own, to their printed digits).
  bool noticeable() const { return found && sigma_s > 1e-3 * sample_interval_s; }
};

// From increments that each hold one sample's rate (a KF-GINS imu.txt, the simulator): a repeat has the rates of
// the increment before it.
ImuStampJitter measure_imu_stamp_jitter(const std::vector<ImuIncrement>& imu);
// From the first tag of each distinct sample [s] (a reader that formed increments between samples, as the tagged
// CSV's trapezoid does, knows them: TaggedImuCsvReport::distinct_sample_tags_s) and how many rows repeated one.
ImuStampJitter measure_imu_stamp_jitter(const std::vector<double>& distinct_sample_tags_s, long rows,
                                        long repeated_rows);

}  // namespace ldv::est
