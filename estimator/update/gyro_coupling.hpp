#pragma once
// How an error of the compensated gyro rate (delta_w, body axes) enters each sensor's measurement
// directly, not through the navigation error: y += G delta_w, with delta_w = J_gyro dx for every
// gyro-driven effect block. One place for the filter's H and for `ldv diagnose`'s candidate sensitivities.
//   gnss_velocity: the antenna turns about the IMU       G = -C_b_n [l x]
//   zaru:          the rate itself is measured           G = I
//   nhc, odometer: the odometer point turns about the IMU G = rows of -C_b_v [l_odo x] ((1 + k) x for odometer)
//   otherwise: no direct coupling (G has no rows).
#include <Eigen/Core>

#include "estimator/effects/effect.hpp"
#include "estimator/update/measurement.hpp"

namespace ldv::est {

Eigen::MatrixXd gyro_error_coupling(SensorName sensor, const LinearizationPoint& lp);

// Adds G J_gyro to H for every gyro-driven block of the layout.
void add_gyro_error_columns(const StateLayout& layout, const LinearizationPoint& lp, Measurement& m);

}  // namespace ldv::est
