// g_sensitivity [rad/s per m/s^2]: gyro bias proportional to the specific force on the same axis,
// w_meas = w + diag(k) f, so delta_w = -diag(f) delta_k.
#include "estimator/effects/vec3_block.hpp"

namespace ldv::est {
namespace {
class GSensitivity final : public Vec3Block {
 public:
  using Vec3Block::Vec3Block;
  const char* name() const override { return "g_sensitivity"; }
  PrintUnit print_unit() const override { return {3600.0 * kRadToDeg * 9.80665, "deg/h/g"}; }
  bool drives_gyro() const override { return true; }
  void imu_jacobians(const LinearizationPoint& lp, Mat3XRef J_gyro, Mat3XRef) const override {
    J_gyro = -lp.f_b_mps2.asDiagonal().toDenseMatrix();
  }
  void apply(const Eigen::Ref<const Eigen::VectorXd>& x, ImuErrorModel& m) const override {
    m.g_sensitivity_rad_per_m += v(x);
  }
};
}  // namespace
std::unique_ptr<Effect> make_g_sensitivity(const FilterOptions& o) { return std::make_unique<GSensitivity>(o.g_sensitivity); }
}  // namespace ldv::est
