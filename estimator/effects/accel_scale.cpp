// accel_scale [-]: diagonal scale-factor error, f_meas = (I + diag(s)) f, so delta_f = -diag(f) delta_s.
#include "estimator/effects/vec3_block.hpp"

namespace ldv::est {
namespace {
class AccelScale final : public Vec3Block {
 public:
  using Vec3Block::Vec3Block;
  const char* name() const override { return "accel_scale"; }
  PrintUnit print_unit() const override { return {1e6, "ppm"}; }
  bool drives_accel() const override { return true; }
  void imu_jacobians(const LinearizationPoint& lp, Mat3XRef, Mat3XRef J_accel) const override {
    J_accel = -lp.f_b_mps2.asDiagonal().toDenseMatrix();
  }
  void apply(const Eigen::Ref<const Eigen::VectorXd>& x, ImuErrorModel& m) const override {
    m.accel_M.diagonal() += v(x);
  }
};
}  // namespace
std::unique_ptr<Effect> make_accel_scale(const FilterOptions& o) { return std::make_unique<AccelScale>(o.accel_scale); }
}  // namespace ldv::est
