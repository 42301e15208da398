// gyro_misalignment [rad]: symmetric non-orthogonality N(m), w_meas = (I + N(m)) w, so delta_w = -N(delta_m) w.
#include "estimator/effects/misalignment_jacobian.hpp"
#include "estimator/effects/vec3_block.hpp"

namespace ldv::est {
namespace {
class GyroMisalignment final : public Vec3Block {
 public:
  using Vec3Block::Vec3Block;
  const char* name() const override { return "gyro_misalignment"; }
  PrintUnit print_unit() const override { return {1e6, "urad"}; }
  bool drives_gyro() const override { return true; }
  void imu_jacobians(const LinearizationPoint& lp, Mat3XRef J_gyro, Mat3XRef) const override {
    J_gyro = -misalignment_jacobian(lp.omega_ib_b_rad_s);
  }
  void apply(const Eigen::Ref<const Eigen::VectorXd>& x, ImuErrorModel& m) const override {
    m.gyro_M += misalignment_matrix(v(x));
  }
};
}  // namespace
std::unique_ptr<Effect> make_gyro_misalignment(const FilterOptions& o) {
  return std::make_unique<GyroMisalignment>(o.gyro_misalignment);
}
}  // namespace ldv::est
