// gravity_anomaly [m/s^2, NED]: true gravity minus WGS84 normal gravity (Gauss-Markov). The INS adds
// the estimate to normal gravity, so delta(dv_n/dt) = delta_g: an identity coupling in n.
#include "estimator/effects/vec3_block.hpp"

namespace ldv::est {
namespace {
class GravityAnomaly final : public Vec3Block {
 public:
  using Vec3Block::Vec3Block;
  const char* name() const override { return "gravity_anomaly"; }
  PrintUnit print_unit() const override { return {1e5, "mGal"}; }
  bool drives_velocity_n() const override { return true; }
  void velocity_n_jacobian(Mat3XRef J) const override { J = Mat3::Identity(); }
  void apply(const Eigen::Ref<const Eigen::VectorXd>& x, ImuErrorModel& m) const override {
    m.gravity_anomaly_n_mps2 = v(x);
  }
};
}  // namespace
std::unique_ptr<Effect> make_gravity_anomaly(const FilterOptions& o) {
  return std::make_unique<GravityAnomaly>(o.gravity_anomaly);
}
}  // namespace ldv::est
