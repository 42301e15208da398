// Zero angular-rate update ("zaru"): at a standstill the IMU does not turn relative to the earth, so the
// compensated gyro rate, averaged over the static detector's window, equals the earth rate in body axes:
// y = mean(w_ib_b) - C_n_b w_ie_n, z = 0. It observes the gyro biases directly, the yaw one included, which
// GNSS alone sees only through turns. Noise: the gyro white noise averaged over the window (as installed:
// times the filter's noise scale) plus aids.zaru_std_rad_s for what the detector lets through.
//   d y / d dx = J_gyro (gyro-driven effects);  d y / d phi = C_n_b [w_ie_n x] (C_n_b_hat = C_n_b (I + [phi x]));
//   the earth rate's change with latitude (1e-11 rad/s per metre) is left out.
#include <cmath>

#include "common/geo/earth_model.hpp"
#include "estimator/update/gyro_coupling.hpp"
#include "estimator/update/updater.hpp"

namespace ldv::est {
namespace {
class ZaruUpdater final : public Updater {
 public:
  const char* name() const override { return "zaru"; }
  std::unique_ptr<Updater> clone() const override { return std::make_unique<ZaruUpdater>(*this); }
  bool due(const AidContext& c) const override {
    return c.detector.is_static() && c.nav.v_n_mps.norm() < c.options.zupt.speed_max_mps &&
           c.f_n_smooth_mps2.head<2>().norm() < c.options.zupt.f_horizontal_max_mps2 &&
           c.nav.t_s - last_t_s_ >= c.options.zupt.period_s;
  }
  void measure(const AidContext& c, std::vector<Measurement>& out) override {
    last_t_s_ = c.nav.t_s;
    const double window_s = c.detector.window_length_s();
    if (!(window_s > 0.0)) return;
    const Mat3 C_n_b = c.lp.C_b_n.transpose();
    const Vec3 w_ie_n = earth::omega_ie_n(c.nav.pos.lat_rad);
    Measurement m(sensors::kZeroAngularRate, 3, c.layout.size());
    m.y = c.detector.mean_rate_rad_s() - C_n_b * w_ie_n;
    m.H.middleCols<3>(kAtt) = C_n_b * skew(w_ie_n);
    add_gyro_error_columns(c.layout, c.lp, m);
    add_effect_columns(c.layout, c.lp, m);
    const Vec3 white_var = c.options.arw_rad_per_sqrt_s.cwiseAbs2() * (c.gyro_noise_scale / window_s);
    const double floor = c.options.aids.zaru_std_rad_s;
    m.R = (white_var.array() + floor * floor).matrix().asDiagonal();
    out.push_back(std::move(m));
  }

 private:
  double last_t_s_ = -1e300;
};
}  // namespace

std::unique_ptr<Updater> make_zaru_updater(const FilterOptions&) { return std::make_unique<ZaruUpdater>(); }

}  // namespace ldv::est
