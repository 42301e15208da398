#pragma once
// A linearised 3-D measurement: innovation y = z_hat - z, H (3 x n, y ~ H delta_x + noise), noise R.
#include "estimator/effects/effect.hpp"
#include "estimator/state/state_layout.hpp"

namespace ldv::est {

struct Measurement {
  MeasurementKind kind = MeasurementKind::kGnssPosition;
  Vec3 y = Vec3::Zero();
  Mat3X H;
  Mat3 R = Mat3::Identity();
};

// Adds each effect block's direct H columns for this measurement kind.
inline void add_effect_columns(const StateLayout& layout, const LinearizationPoint& lp, Measurement& m) {
  for (const auto& b : layout.blocks())
    if (b.effect->enters(m.kind)) b.effect->measurement_jacobian(m.kind, lp, m.H.middleCols(b.offset, b.dim));
}

// Lets each block entering this measurement take its part out of the noise R (call after setting R).
inline void adjust_effect_noise(const StateLayout& layout, Measurement& m) {
  for (const auto& b : layout.blocks())
    if (b.effect->enters(m.kind)) b.effect->adjust_measurement_noise(m.kind, m.R);
}

}  // namespace ldv::est
