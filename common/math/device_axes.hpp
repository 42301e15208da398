#pragma once
// Device axes to the body's front-right-down: axes[i] is the device axis (1-based, signed) that body axis i is (a
// front-left-up IMU: 1 -2 -3). Used by every reader of a user's own IMU layout (--csv-axes, a table's `axes`).
#include <cstdlib>
#include <vector>

#include "common/math/rotation.hpp"

namespace ldv {

// A signed permutation of 1 2 3.
inline bool is_device_axes(const std::vector<int>& axes) {
  int seen = 0;
  for (const int a : axes)
    if (std::abs(a) >= 1 && std::abs(a) <= 3) seen |= 1 << std::abs(a);
  return axes.size() == 3 && seen == 0b1110;
}

// v (device axes) in front-right-down; axes must pass is_device_axes.
inline Vec3 device_to_frd(const Vec3& v, const std::vector<int>& axes) {
  Vec3 out;
  for (int i = 0; i < 3; ++i) out(i) = (axes[i] > 0 ? 1.0 : -1.0) * v(std::abs(axes[i]) - 1);
  return out;
}

}  // namespace ldv
