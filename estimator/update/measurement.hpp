#pragma once
// A linearised measurement of any size m: innovation y = z_hat - z (m), H (m x n, y ~ H delta_x + noise),
// noise R (m x m), and the sensor it came from. Its chi-square gate has m degrees of freedom.
#include <Eigen/Core>

#include "estimator/effects/effect.hpp"
#include "estimator/state/state_layout.hpp"
#include "estimator/update/sensor_names.hpp"

namespace ldv::est {

struct Measurement {
  SensorName sensor = sensors::kGnssPosition;
  Eigen::VectorXd y;
  Eigen::MatrixXd H;
  Eigen::MatrixXd R;
  // A GNSS measurement: when used, it ends an outage (status bit, ZUPTs held back while GNSS is recent).
  bool gnss = false;
  // Where a step of the measured quantity shows in the state (kPos, kVel), for the step confirmation
  // (NavFilter): consecutive measurements beyond the gate that agree open this block's variance and are
  // taken. -1: the sensor has no such steps (an aid's "zero" does not jump).
  int step_block = -1;
  // A GNSS position's solution quality as NoiseAdaptation classes it (0 fixed, 1 float, 2 other): each has its own
  // factor on the stated variance.
  int gnss_class = 0;

  int rows() const { return static_cast<int>(y.size()); }
  // y, H (zero) and R (zero) sized for `rows` rows over the layout's states.
  Measurement(SensorName name, int rows, int states)
      : sensor(name),
        y(Eigen::VectorXd::Zero(rows)),
        H(Eigen::MatrixXd::Zero(rows, states)),
        R(Eigen::MatrixXd::Zero(rows, rows)) {}
  Measurement() = default;
};

// Adds each effect block's direct H columns for this measurement's sensor.
inline void add_effect_columns(const StateLayout& layout, const LinearizationPoint& lp, Measurement& m) {
  for (const auto& b : layout.blocks())
    if (b.effect->enters(m.sensor)) b.effect->measurement_jacobian(m.sensor, lp, m.H.middleCols(b.offset, b.dim));
}

// Lets each block entering this measurement take its part out of the noise R (call after setting R).
inline void adjust_effect_noise(const StateLayout& layout, Measurement& m) {
  for (const auto& b : layout.blocks())
    if (b.effect->enters(m.sensor)) b.effect->adjust_measurement_noise(m.sensor, m.R);
}

}  // namespace ldv::est
