// accel_misalignment [rad]: symmetric non-orthogonality N(m), f_meas = (I + N(m)) f, so delta_f = -N(delta_m) f.
#include "estimator/effects/misalignment_jacobian.hpp"
#include "estimator/effects/vec3_block.hpp"

namespace ldv::est {
namespace {
class AccelMisalignment final : public Vec3Block {
 public:
  using Vec3Block::Vec3Block;
  const char* name() const override { return "accel_misalignment"; }
  PrintUnit print_unit() const override { return {1e6, "urad"}; }
  bool drives_accel() const override { return true; }
  void imu_jacobians(const LinearizationPoint& lp, Mat3XRef, Mat3XRef J_accel) const override {
    J_accel = -misalignment_jacobian(lp.f_b_mps2);
  }
  void apply(const Eigen::Ref<const Eigen::VectorXd>& x, ImuErrorModel& m) const override {
    m.accel_M += misalignment_matrix(v(x));
  }
};
}  // namespace
std::unique_ptr<Effect> make_accel_misalignment(const FilterOptions& o) {
  return std::make_unique<AccelMisalignment>(o.accel_misalignment);
}
}  // namespace ldv::est
