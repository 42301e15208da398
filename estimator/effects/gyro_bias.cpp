// gyro_bias [rad/s]: additive gyro bias, w_meas = w + b_g. Compensation w = w_meas - b_g, so delta_w = -delta_b_g.
#include "estimator/effects/vec3_block.hpp"

namespace ldv::est {
namespace {
class GyroBias final : public Vec3Block {
 public:
  using Vec3Block::Vec3Block;
  const char* name() const override { return "gyro_bias"; }
  PrintUnit print_unit() const override { return {3600.0 * kRadToDeg, "deg/h"}; }
  bool drives_gyro() const override { return true; }
  void imu_jacobians(const LinearizationPoint&, Mat3XRef J_gyro, Mat3XRef) const override {
    J_gyro = -Mat3::Identity();
  }
  void apply(const Eigen::Ref<const Eigen::VectorXd>& x, ImuErrorModel& m) const override { m.gyro_bias_rad_s += v(x); }
};
}  // namespace
std::unique_ptr<Effect> make_gyro_bias(const FilterOptions& o) { return std::make_unique<GyroBias>(o.gyro_bias); }
}  // namespace ldv::est
