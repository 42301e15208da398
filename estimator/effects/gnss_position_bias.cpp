// gnss_position_bias [m, NED]: the slowly varying part of the GNSS position error (RTK multipath,
// residual troposphere, float ambiguities), first-order Gauss-Markov with sigma and time constant from
// the options (`ldv: gnss_bias_sigma_m`, `gnss_bias_tau_s`). The receiver reports
//   z = r_ant + b + white noise,  so  z_hat = r_ant_hat + b_hat  and  d(z_hat - z)/d(delta_b) = I.
// The reported std covers both parts: the white variance is reported^2 - sigma^2 (floored at a quarter
// of the reported variance when a receiver reports less than sigma). The estimate decays with the
// Gauss-Markov time constant between fixes (unlike the sensor blocks, whose nominal is held), so the
// prediction across an outage is the expected bias.
#include <cmath>

#include "estimator/effects/vec3_block.hpp"

namespace ldv::est {
namespace {
class GnssPositionBias final : public Vec3Block {
 public:
  using Vec3Block::Vec3Block;
  const char* name() const override { return "gnss_position_bias"; }
  std::vector<std::string> state_names() const override {
    return {"gnss_position_bias_n", "gnss_position_bias_e", "gnss_position_bias_d"};
  }
  PrintUnit print_unit() const override { return {1e2, "cm"}; }
  bool enters(SensorName k) const override { return k == sensors::kGnssPosition; }
  void measurement_jacobian(SensorName k, const LinearizationPoint&, MatXRef H) const override {
    if (k == sensors::kGnssPosition) H = Mat3::Identity();
  }
  void adjust_measurement_noise(SensorName k, Eigen::MatrixXd& R) const override {
    if (k != sensors::kGnssPosition) return;
    for (int i = 0; i < 3; ++i) R(i, i) = std::max(R(i, i) - o_.sigma(i) * o_.sigma(i), 0.25 * R(i, i));
  }
  void propagate_nominal(Eigen::Ref<Eigen::VectorXd> x, double dt_s) const override {
    if (o_.process == BlockOptions::Process::kGaussMarkov && o_.corr_time_s > 0.0)
      x *= std::exp(-dt_s / o_.corr_time_s);
  }
  void apply(const Eigen::Ref<const Eigen::VectorXd>& x, ImuErrorModel& m) const override {
    m.gnss_position_bias_n_m = v(x);
  }
};
}  // namespace
std::unique_ptr<Effect> make_gnss_position_bias(const FilterOptions& o) {
  return std::make_unique<GnssPositionBias>(o.gnss_position_bias);
}
}  // namespace ldv::est
