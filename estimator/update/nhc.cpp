// Non-holonomic constraint ("nhc"): a land vehicle does not slide sideways nor leave the road, so the
// lateral and vertical velocity of its rear-axle centre, in vehicle axes, are zero (vehicle_velocity.hpp):
// y = (v_v_y, v_v_z) predicted, z = 0. Applied every aids.nhc_period_s; its noise covers the slip and
// suspension motion a real car has (aids.nhc_std_mps).
#include <algorithm>

#include "estimator/update/gyro_coupling.hpp"
#include "estimator/update/updater.hpp"
#include "estimator/update/vehicle_velocity.hpp"

namespace ldv::est {
namespace {
class NhcUpdater final : public Updater {
 public:
  const char* name() const override { return "nhc"; }
  std::unique_ptr<Updater> clone() const override { return std::make_unique<NhcUpdater>(*this); }
  bool due(const AidContext& c) const override { return c.nav.t_s - last_t_s_ >= c.options.aids.nhc_period_s; }
  void measure(const AidContext& c, std::vector<Measurement>& out) override {
    last_t_s_ = c.nav.t_s;
    const VehicleVelocity vv = vehicle_velocity(c.nav, c.lp, c.layout);
    Measurement m(sensors::kNonHolonomic, 2, c.layout.size());
    m.y = vv.v_v_mps.tail<2>();
    m.H = vv.H.bottomRows<2>();
    add_gyro_error_columns(c.layout, c.lp, m);
    add_effect_columns(c.layout, c.lp, m);
    const double sd = c.options.aids.nhc_std_mps;
    m.R = Eigen::Matrix2d::Identity() * sd * sd;
    out.push_back(std::move(m));
  }

 private:
  double last_t_s_ = -1e300;
};
}  // namespace

std::unique_ptr<Updater> make_nhc_updater(const FilterOptions&) { return std::make_unique<NhcUpdater>(); }

}  // namespace ldv::est
