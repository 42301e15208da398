// odometer_lever_arm [m]: the odometer point (rear-axle centre) minus the IMU centre, body axes. Its velocity
// v_b = C_n_b v_n + w_nb_b x l, so d v_v / d l = C_b_v [w_nb_b x] (nhc: rows y, z; odometer: (1 + k) row x).
// Observable only through turns (a roof IMU 1.5 m ahead of the axle sees 0.45 m/s of lateral velocity at
// 0.3 rad/s of yaw rate, which NHC would otherwise read as a violation).
#include "common/math/rotation.hpp"
#include "estimator/effects/vec3_block.hpp"

namespace ldv::est {
namespace {
class OdometerLeverArm final : public Vec3Block {
 public:
  using Vec3Block::Vec3Block;
  const char* name() const override { return "odometer_lever_arm"; }
  PrintUnit print_unit() const override { return {1.0, "m"}; }
  bool enters(SensorName k) const override { return k == sensors::kNonHolonomic || k == sensors::kOdometer; }
  void measurement_jacobian(SensorName k, const LinearizationPoint& lp, MatXRef H) const override {
    const Mat3 J = lp.C_b_v * skew(lp.omega_nb_b_rad_s);
    if (k == sensors::kNonHolonomic) H = J.bottomRows<2>();
    if (k == sensors::kOdometer) H = (1.0 + lp.odometer_scale) * J.topRows<1>();
  }
  void apply(const Eigen::Ref<const Eigen::VectorXd>& x, ImuErrorModel& m) const override {
    m.odometer_lever_arm_b_m = v(x);
  }
};
}  // namespace
std::unique_ptr<Effect> make_odometer_lever_arm(const FilterOptions& o) {
  return std::make_unique<OdometerLeverArm>(o.odometer_lever_arm);
}
}  // namespace ldv::est
