#pragma once
// Paths and helpers for the real calibration logs in ../shared/data/calib.
#include <Eigen/Dense>
#include <string>

#include "common/math/rotation.hpp"

namespace ldv::calib::testing {

inline std::string shared_data(const std::string& rel) { return std::string(LDV_SHARED_DATA_DIR) + "/" + rel; }

// Sensitivity of each axis (norm of the sensor matrix row: the row is the axis' sensitive direction times
// its gain) and the non-orthogonality between axis pairs: 90 deg minus the angle between sensitive
// directions, (y-z, z-x, x-y) [rad]. Both are invariant to a rotation of the whole triad, so they compare
// matrices that include a mounting rotation (a vendor's) with our symmetric ones.
inline Vec3 row_gains(const Mat3& M) { return Vec3(M.row(0).norm(), M.row(1).norm(), M.row(2).norm()); }

inline Vec3 axis_non_orthogonality_rad(const Mat3& M) {
  auto angle = [&](int i, int j) {
    return std::asin(M.row(i).dot(M.row(j)) / (M.row(i).norm() * M.row(j).norm()));
  };
  return Vec3(angle(1, 2), angle(2, 0), angle(0, 1));
}

}  // namespace ldv::calib::testing
