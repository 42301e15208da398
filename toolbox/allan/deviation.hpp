#pragma once
// Frequency-stability deviations of a phase series, exactly as NIST SP 1065 and Stable32 define them.
//
// The input is always phase x[0..N-1] sampled every tau0 (for an inertial sensor: the integrated
// rate, i.e. angle or velocity; for a clock: time error in seconds). The result is in the unit of
// the rate (x per second). Every deviation costs O(N) per averaging factor m (tau = m tau0) and
// uses every sample: the non-overlapped ADEV/HDEV stride through the data, nothing is decimated.
#include <string>
#include <vector>

namespace ldv::allan {

enum class Deviation { kAdev, kOadev, kMdev, kHdev, kOhdev, kTdev };

const char* deviation_name(Deviation d);                 // "adev", "oadev", ...
Deviation parse_deviation(const std::string& name);      // throws std::invalid_argument

struct DeviationPoint {
  long m = 0;           // averaging factor, tau = m tau0
  double tau_s = 0.0;
  double dev = 0.0;     // the deviation at tau (TDEV: in the unit of x)
  long n_terms = 0;     // number of analysis points (terms in the sum), as Stable32's "#" column
};

// Largest m the deviation can be computed for with N phase points (at least one term).
long max_averaging_factor(Deviation d, long n_phase);

// Number of terms of the sum for m (0 when m is too large).
long analysis_points(Deviation d, long n_phase, long m);

// The deviation at one averaging factor. Throws std::invalid_argument when m < 1 or the data is
// too short for m (the caller names the file).
DeviationPoint deviation_at(const std::vector<double>& x, double tau0_s, Deviation d, long m);

// Many averaging factors; points are returned in the order given.
std::vector<DeviationPoint> deviations(const std::vector<double>& x, double tau0_s, Deviation d,
                                       const std::vector<long>& ms);

}  // namespace ldv::allan
