#include "toolbox/allan/confidence.hpp"

#include <cmath>

#include "common/math/chi_square.hpp"
#include "toolbox/allan/edf.hpp"
#include "toolbox/allan/noise_id.hpp"

namespace ldv::allan {

Interval chi_square_interval(double dev, double edf, double confidence) {
  if (!(edf > 0.0)) return {dev, dev};
  const double tail = 0.5 * (1.0 - confidence);
  const double chi_lo = math::chi_square_quantile(tail, edf);
  const double chi_hi = math::chi_square_quantile(1.0 - tail, edf);
  return {dev * std::sqrt(edf / chi_hi), dev * std::sqrt(edf / chi_lo)};
}

std::vector<StabilityPoint> with_confidence(const PhaseSeries& s, Deviation dev,
                                            const std::vector<DeviationPoint>& points, double confidence) {
  std::vector<StabilityPoint> out;
  out.reserve(points.size());
  const long n_phase = static_cast<long>(s.x.size());
  int last_alpha = 0;  // carried over when a point has too few samples for either identification
  for (const DeviationPoint& p : points) {
    StabilityPoint sp;
    sp.point = p;
    const NoiseId id = identify_noise(s, p.m, dev);
    sp.alpha = id.valid ? id.alpha : last_alpha;
    sp.alpha_by_acf = id.valid && id.by_acf;
    last_alpha = sp.alpha;
    sp.edf = greenhall_edf(dev, sp.alpha, p.m, n_phase);
    sp.interval = chi_square_interval(p.dev, sp.edf, confidence);
    out.push_back(sp);
  }
  return out;
}

std::vector<StabilityPoint> stability(const PhaseSeries& s, Deviation dev, const std::vector<long>& ms,
                                      double confidence) {
  return with_confidence(s, dev, deviations(s.x, s.tau0_s, dev, ms), confidence);
}

}  // namespace ldv::allan
