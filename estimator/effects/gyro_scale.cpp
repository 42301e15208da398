// gyro_scale [-]: diagonal scale-factor error, w_meas = (I + diag(s)) w, so delta_w = -diag(w) delta_s.
#include "estimator/effects/vec3_block.hpp"

namespace ldv::est {
namespace {
class GyroScale final : public Vec3Block {
 public:
  using Vec3Block::Vec3Block;
  const char* name() const override { return "gyro_scale"; }
  PrintUnit print_unit() const override { return {1e6, "ppm"}; }
  bool drives_gyro() const override { return true; }
  void imu_jacobians(const LinearizationPoint& lp, Mat3XRef J_gyro, Mat3XRef) const override {
    J_gyro = -lp.omega_ib_b_rad_s.asDiagonal().toDenseMatrix();
  }
  void apply(const Eigen::Ref<const Eigen::VectorXd>& x, ImuErrorModel& m) const override {
    m.gyro_M.diagonal() += v(x);
  }
};
}  // namespace
std::unique_ptr<Effect> make_gyro_scale(const FilterOptions& o) { return std::make_unique<GyroScale>(o.gyro_scale); }
}  // namespace ldv::est
