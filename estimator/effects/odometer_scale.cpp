// odometer_scale [-]: the odometer reads (1 + k) times the true forward speed (tyre wear, pressure, load:
// typically 0.1-2 %). z_hat = (1 + k_hat) v_v_x  =>  d y / d k = v_v_x. Printed in percent.
#include "estimator/effects/effect.hpp"
#include "estimator/options.hpp"
#include "estimator/update/vehicle_velocity.hpp"

namespace ldv::est {
namespace {
class OdometerScale final : public Effect {
 public:
  explicit OdometerScale(const FilterOptions& o) : init_(o.odometer_scale_init), std_(o.odometer_scale_std) {}
  const char* name() const override { return "odometer_scale"; }
  int dim() const override { return 1; }
  std::vector<std::string> state_names() const override { return {"odometer_scale"}; }
  PrintUnit print_unit() const override { return {1e2, "%"}; }
  void prior(Eigen::Ref<Eigen::VectorXd> mean, Eigen::Ref<Eigen::VectorXd> std) const override {
    mean(0) = init_;
    std(0) = std_;
  }
  bool enters(SensorName k) const override { return k == sensors::kOdometer; }
  void measurement_jacobian(SensorName, const LinearizationPoint& lp, MatXRef H) const override {
    H(0, 0) = (lp.C_b_v * odometer_point_velocity_b(lp)).x();
  }
  void apply(const Eigen::Ref<const Eigen::VectorXd>& x, ImuErrorModel& m) const override { m.odometer_scale = x(0); }

 private:
  double init_, std_;
};
}  // namespace
std::unique_ptr<Effect> make_odometer_scale(const FilterOptions& o) { return std::make_unique<OdometerScale>(o); }
}  // namespace ldv::est
