#pragma once
#include "common/math/rotation.hpp"

namespace ldv::est {
// d(N(m) u)/dm for the symmetric non-orthogonality matrix N(m) of docs/effects.md.
inline Mat3 misalignment_jacobian(const Vec3& u) {
  Mat3 J;
  J << 0.0, u.z(), u.y(),  //
      u.z(), 0.0, u.x(),   //
      u.y(), u.x(), 0.0;
  return J;
}
}  // namespace ldv::est
