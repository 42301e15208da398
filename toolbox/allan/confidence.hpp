#pragma once
// Deviations with their confidence intervals: noise type at each tau, Greenhall EDF, chi-square.
#include <vector>

#include "toolbox/allan/deviation.hpp"
#include "toolbox/allan/phase_series.hpp"

namespace ldv::allan {

// Stable32's default: a 1-sigma (68.3 %) interval.
inline constexpr double kOneSigmaConfidence = 0.683;

struct Interval {
  double lo = 0.0, hi = 0.0;
};

// NIST SP 1065 eq. (45): sigma^2 edf / chi2_{p} bounds the true variance. Returns {dev, dev} when
// edf <= 0 (no estimate of the uncertainty).
Interval chi_square_interval(double dev, double edf, double confidence);

struct StabilityPoint {
  DeviationPoint point;
  int alpha = 0;        // identified noise exponent used for the EDF
  bool alpha_by_acf = false;  // identified by the lag-1 autocorrelation (else B1 ratio / carried over)
  double edf = 0.0;     // equivalent degrees of freedom
  Interval interval;    // bounds of the deviation at the requested confidence
};

// The deviation at every m, each with its noise identification, EDF and interval. m too large for
// the data throws std::invalid_argument.
std::vector<StabilityPoint> stability(const PhaseSeries& s, Deviation dev, const std::vector<long>& ms,
                                      double confidence = kOneSigmaConfidence);

// Adds noise type, EDF and interval to already computed points (the benchmarked path computes the
// deviations in parallel first).
std::vector<StabilityPoint> with_confidence(const PhaseSeries& s, Deviation dev,
                                            const std::vector<DeviationPoint>& points, double confidence);

}  // namespace ldv::allan
