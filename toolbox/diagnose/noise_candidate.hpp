#pragma once
// The GNSS and the IMU noise as candidates of the stepwise selection (issue 47, "effects before noise"): a receiver
// that states less than it delivers makes every effect's rerun look worse (each pulls the state towards noise) and the
// model check fail with nothing to name. The factors the innovations call for per solution quality (the split
// adaptation's, estimator/filter/noise_adaptation.hpp) are rerun as ldv.gnss_variance_scale and judged on the same
// likelihood and penalty as every effect: the largest penalised gain goes first, a noise or an effect, and the next
// step screens with it. The factors come from the fix-to-fix differences, where a structured effect barely shows, so
// a missing lever arm or lag does not make a GNSS noise candidate. The IMU's factor is the excess the differences do
// not show (a prediction too confident for the IMU's noise); a structured effect shows there too, which is why it
// must beat every effect's rerun to be taken, and is measured again after each effect added.
#include <optional>

#include "estimator/filter/noise_adaptation.hpp"
#include "toolbox/diagnose/confirmation.hpp"

namespace ldv::diag {

inline constexpr const char* kGnssNoiseCandidate = "gnss_noise";
inline constexpr const char* kImuNoiseCandidate = "imu_noise";

// The noise `model`'s innovations call for: a pass with the split noise adaptation over the inputs.
struct MeasuredNoise {
  est::NoiseAdaptation adaptation;   // the GNSS factors per solution quality and the IMU's, as the pass ended
  est::ImuNoiseScale imu_psd_scale;  // the IMU white-noise PSDs the pass ended with, on the model's (floor x factor)
};
// nullopt: the pass failed (the diagnosis's own runs say why).
std::optional<MeasuredNoise> measure_noise(const DiagnoseInputs& in, const est::FilterOptions& model);

// The rerun with each solution quality's stated variance times its factor where the factor is beyond 1 by more
// than two sigma, judged against `base` with one parameter per class rescaled (nullopt: no class is). Its
// estimate lists the classes rescaled and their factors.
std::optional<Confirmation> confirm_gnss_noise(const DiagnoseInputs& in, const est::FilterOptions& model,
                                               const FilterRun& base, const est::NoiseAdaptation& measured,
                                               double long_run_factor, double effective_n);

// The rerun with the IMU white-noise PSDs as the pass ended them, where its factor is beyond 1 by more than two
// sigma; one parameter. Its estimate is the PSD factors [gyro, accel] on the model's.
std::optional<Confirmation> confirm_imu_noise(const DiagnoseInputs& in, const est::FilterOptions& model,
                                              const FilterRun& base, const MeasuredNoise& measured,
                                              double long_run_factor, double effective_n);

}  // namespace ldv::diag
