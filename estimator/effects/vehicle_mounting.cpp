// vehicle_mounting [rad]: the small rotation mu of the IMU in the vehicle left after the coarse mounting
// (FilterOptions::aids.mounting_rpy_rad): C_b_v = C_b_v_coarse C(mu), C(mu) the roll-pitch-yaw rotation of
// mu (~ I + [mu x]). The vehicle-frame aids see it: v_v = C_b_v v_b, so with mu_hat = mu + delta,
//   d v_v / d delta = -C_b_v [v_b x]   (nhc: rows y, z; odometer: (1 + k) row x).
// Without it, a 2 deg mounting error turns every metre per second of speed into 3.5 cm/s of "lateral
// velocity" that the NHC forces onto the heading and the accelerometer biases (smeared, not diagnosed).
#include "common/math/rotation.hpp"
#include "estimator/effects/vec3_block.hpp"
#include "estimator/update/vehicle_velocity.hpp"

namespace ldv::est {
namespace {
class VehicleMounting final : public Vec3Block {
 public:
  using Vec3Block::Vec3Block;
  const char* name() const override { return "vehicle_mounting"; }
  std::vector<std::string> state_names() const override {
    return {"vehicle_mounting_roll", "vehicle_mounting_pitch", "vehicle_mounting_yaw"};
  }
  PrintUnit print_unit() const override { return {kRadToDeg, "deg"}; }
  bool enters(SensorName k) const override { return k == sensors::kNonHolonomic || k == sensors::kOdometer; }
  void measurement_jacobian(SensorName k, const LinearizationPoint& lp, MatXRef H) const override {
    const Mat3 J = -lp.C_b_v * skew(odometer_point_velocity_b(lp));
    if (k == sensors::kNonHolonomic) H = J.bottomRows<2>();
    if (k == sensors::kOdometer) H = (1.0 + lp.odometer_scale) * J.topRows<1>();
  }
  void apply(const Eigen::Ref<const Eigen::VectorXd>& x, ImuErrorModel& m) const override {
    m.vehicle_mounting_rad = v(x);
  }
};
}  // namespace
std::unique_ptr<Effect> make_vehicle_mounting(const FilterOptions& o) {
  return std::make_unique<VehicleMounting>(o.vehicle_mounting);
}
}  // namespace ldv::est
