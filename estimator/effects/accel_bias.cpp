// accel_bias [m/s^2]: additive accelerometer bias, f_meas = f + b_a, so delta_f = -delta_b_a.
#include "estimator/effects/vec3_block.hpp"

namespace ldv::est {
namespace {
class AccelBias final : public Vec3Block {
 public:
  using Vec3Block::Vec3Block;
  const char* name() const override { return "accel_bias"; }
  PrintUnit print_unit() const override { return {1e5, "mGal"}; }
  bool drives_accel() const override { return true; }
  void imu_jacobians(const LinearizationPoint&, Mat3XRef, Mat3XRef J_accel) const override {
    J_accel = -Mat3::Identity();
  }
  void apply(const Eigen::Ref<const Eigen::VectorXd>& x, ImuErrorModel& m) const override { m.accel_bias_mps2 += v(x); }
};
}  // namespace
std::unique_ptr<Effect> make_accel_bias(const FilterOptions& o) { return std::make_unique<AccelBias>(o.accel_bias); }
}  // namespace ldv::est
