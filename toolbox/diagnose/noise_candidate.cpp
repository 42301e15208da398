#include "toolbox/diagnose/noise_candidate.hpp"

#include <exception>
#include <string>
#include <vector>

#include "estimator/filter/nav_filter.hpp"
#include "estimator/run/run_navigation.hpp"

namespace ldv::diag {

std::optional<est::NoiseAdaptation> measure_gnss_noise(const DiagnoseInputs& in, const est::FilterOptions& model) {
  est::FilterOptions o = model;
  o.adapt_imu_noise = o.split_noise_adaptation = true;
  try {
    est::NavFilter filter(o);
    est::run_navigation(in.imu, in.gnss, in.cfg, filter, est::RunCallbacks{}, nullptr, &in.others);
    return filter.noise_adaptation();
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

std::optional<Confirmation> confirm_gnss_noise(const DiagnoseInputs& in, const est::FilterOptions& model,
                                               const FilterRun& base, const est::NoiseAdaptation& measured,
                                               double long_run_factor, double effective_n) {
  Confirmation c;
  c.effect = kGnssNoiseCandidate;
  c.options = model;
  std::vector<double> factors, sigmas;
  for (int k = 0; k < est::NoiseAdaptation::kGnssClasses; ++k) {
    const double factor = measured.gnss_scale(k), sigma = measured.gnss_scale_sigma(k);
    if (measured.gnss_fixes(k) == 0 || !(factor - 2.0 * sigma > 1.0)) continue;
    c.options.gnss_variance_scale[k] *= factor;
    factors.push_back(factor);
    sigmas.push_back(sigma);
    c.estimate.state_names.push_back(est::NoiseAdaptation::gnss_class_name(k));
  }
  if (factors.empty()) return std::nullopt;
  c.estimate.name = kGnssNoiseCandidate;
  c.estimate.unit = est::PrintUnit{1.0, "x the stated variance"};
  c.estimate.value_si = Eigen::Map<const Eigen::VectorXd>(factors.data(), static_cast<Eigen::Index>(factors.size()));
  c.estimate.std_si = Eigen::Map<const Eigen::VectorXd>(sigmas.data(), static_cast<Eigen::Index>(sigmas.size()));
  c.run = run_filter(in, c.options);
  judge_rerun(c, base, static_cast<int>(factors.size()), long_run_factor, effective_n);
  return c;
}

}  // namespace ldv::diag
