// time_offset [s]: GNSS time tag minus IMU time; the fix labelled t was taken at IMU time t - tau.
// The filter applies the fix at t - tau_hat, where the truth is r(t - tau) = r(t - tau_hat + delta_tau),
// so z_hat - z = ... - v_ant delta_tau (position) and - a delta_tau (velocity).
#include "estimator/effects/effect.hpp"
#include "estimator/options.hpp"

namespace ldv::est {
namespace {
class TimeOffset final : public Effect {
 public:
  explicit TimeOffset(const FilterOptions& o) : init_s_(o.time_offset_init_s), std_s_(o.time_offset_std_s) {}
  const char* name() const override { return "time_offset"; }
  int dim() const override { return 1; }
  std::vector<std::string> state_names() const override { return {"time_offset"}; }
  PrintUnit print_unit() const override { return {1e3, "ms"}; }
  void prior(Eigen::Ref<Eigen::VectorXd> mean, Eigen::Ref<Eigen::VectorXd> std) const override {
    mean(0) = init_s_;
    std(0) = std_s_;
  }
  bool enters(SensorName k) const override { return k == sensors::kGnssPosition || k == sensors::kGnssVelocity; }
  void measurement_jacobian(SensorName k, const LinearizationPoint& lp, MatXRef H) const override {
    if (k == sensors::kGnssPosition) H.col(0) = -lp.v_ant_n_mps;
    if (k == sensors::kGnssVelocity) H.col(0) = -lp.a_n_mps2;
  }
  void apply(const Eigen::Ref<const Eigen::VectorXd>& x, ImuErrorModel& m) const override { m.time_offset_s = x(0); }

 private:
  double init_s_, std_s_;
};
}  // namespace
std::unique_ptr<Effect> make_time_offset(const FilterOptions& o) { return std::make_unique<TimeOffset>(o); }
}  // namespace ldv::est
