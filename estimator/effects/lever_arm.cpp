// lever_arm [m]: antenna minus IMU centre in body axes, r_ant = r_imu + C_b_n l.
//   position:  d(r_ant)/dl = C_b_n
//   velocity:  v_ant = v + C_b_n (w x l) - w_in x (C_b_n l)  =>  d/dl = C_b_n [w x] - [w_in x] C_b_n
#include "estimator/effects/vec3_block.hpp"

namespace ldv::est {
namespace {
class LeverArm final : public Vec3Block {
 public:
  using Vec3Block::Vec3Block;
  const char* name() const override { return "lever_arm"; }
  PrintUnit print_unit() const override { return {1.0, "m"}; }
  bool enters(SensorName k) const override { return k == sensors::kGnssPosition || k == sensors::kGnssVelocity; }
  void measurement_jacobian(SensorName k, const LinearizationPoint& lp, MatXRef H) const override {
    if (k == sensors::kGnssPosition) H = lp.C_b_n;
    if (k == sensors::kGnssVelocity) H = lp.C_b_n * skew(lp.omega_ib_b_rad_s) - skew(lp.omega_in_n_rad_s) * lp.C_b_n;
  }
  void apply(const Eigen::Ref<const Eigen::VectorXd>& x, ImuErrorModel& m) const override { m.lever_arm_b_m = v(x); }
};
}  // namespace
std::unique_ptr<Effect> make_lever_arm(const FilterOptions& o) { return std::make_unique<LeverArm>(o.lever_arm); }
}  // namespace ldv::est
