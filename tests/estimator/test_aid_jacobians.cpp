// The land-vehicle aids' H (nhc, odometer, zaru) against numerical derivatives of their nonlinear models
// written here from the definitions, independently of estimator/update: the velocity of the odometer point
// in vehicle axes v_v = C_b_v (C_n_b v_n + (w_ib_b - C_n_b w_in_n) x l), its forward component read by an
// odometer with scale (1 + k), and the body rate relative to the earth at a standstill. Every error state
// is perturbed as estimate = truth + eps (the filter's convention), including the effects that enter
// the aids (vehicle_mounting, odometer_lever_arm, odometer_scale) and the gyro errors.
#include <gtest/gtest.h>

#include "common/geo/earth_model.hpp"
#include "estimator/options.hpp"
#include "estimator/state/state_layout.hpp"
#include "estimator/update/odometer.hpp"
#include "estimator/update/updater.hpp"

namespace ldv::est {
namespace {

NavState perturbed_nav(const NavState& s, const Eigen::Matrix<double, 9, 1>& e) {
  NavState y = s;
  y.pos = earth::offset_ned(s.pos, e.segment<3>(0));
  y.v_n_mps += e.segment<3>(3);
  y.q_b_n = quat_from_rotvec(-e.segment<3>(6)) * s.q_b_n;
  return y;
}

// What the vehicle-frame aids see, from the definitions.
struct AidTruth {
  NavState nav;
  Vec3 w_ib_b, lever_odo_b;
  Mat3 C_b_v;
  double odo_scale = 0.0;
};

Vec3 vehicle_velocity_model(const AidTruth& t) {
  const Mat3 C_n_b = t.nav.C_b_n().transpose();
  const Vec3 w_in =
      earth::omega_ie_n(t.nav.pos.lat_rad) + earth::omega_en_n(t.nav.pos.lat_rad, t.nav.pos.h_m, t.nav.v_n_mps);
  const Vec3 w_nb = t.w_ib_b - C_n_b * w_in;
  return t.C_b_v * (C_n_b * t.nav.v_n_mps + w_nb.cross(t.lever_odo_b));
}

LinearizationPoint lp_of(const AidTruth& t) {
  LinearizationPoint lp;
  lp.C_b_n = t.nav.C_b_n();
  lp.omega_ib_b_rad_s = t.w_ib_b;
  lp.omega_in_n_rad_s =
      earth::omega_ie_n(t.nav.pos.lat_rad) + earth::omega_en_n(t.nav.pos.lat_rad, t.nav.pos.h_m, t.nav.v_n_mps);
  lp.v_n_mps = t.nav.v_n_mps;
  lp.omega_nb_b_rad_s = t.w_ib_b - lp.C_b_n.transpose() * lp.omega_in_n_rad_s;
  lp.C_b_v = t.C_b_v;
  lp.odometer_lever_arm_b_m = t.lever_odo_b;
  lp.odometer_scale = t.odo_scale;
  return lp;
}

class AidJacobians : public ::testing::Test {
 protected:
  void SetUp() override {
    opt.aids.enabled = {"nhc", "zaru"};
    layout = StateLayout({"gyro_bias", "gyro_scale", "vehicle_mounting", "odometer_lever_arm", "odometer_scale"}, opt);
    truth.nav.pos = {31.0 * kDegToRad, 114.0 * kDegToRad, 30.0};
    truth.nav.v_n_mps = Vec3(8.0, 6.0, -0.3);
    truth.nav.q_b_n = quat_from_euler(Vec3(0.05, -0.03, 0.9));
    truth.w_ib_b = Vec3(0.02, -0.03, 0.4);
    truth.lever_odo_b = Vec3(-1.4, 0.3, 1.1);
    // Mounted backwards and upside down (the coarse mounting): the residual states start at zero.
    truth.C_b_v = C_b_n_from_euler(Vec3(kPi, 0.0, kPi));
    truth.odo_scale = 0.01;
  }
  // The truth with every error state i perturbed by eps (estimate = truth + eps).
  AidTruth perturbed(int i, double eps) const {
    AidTruth t = truth;
    Eigen::Matrix<double, 9, 1> e = Eigen::Matrix<double, 9, 1>::Zero();
    if (i < 9) e(i) = eps;
    t.nav = perturbed_nav(truth.nav, e);
    const int o_bg = layout.find("gyro_bias")->offset, o_sg = layout.find("gyro_scale")->offset;
    const int o_m = layout.find("vehicle_mounting")->offset, o_l = layout.find("odometer_lever_arm")->offset;
    const int o_k = layout.find("odometer_scale")->offset;
    if (i >= o_bg && i < o_bg + 3) t.w_ib_b(i - o_bg) -= eps;                           // w_hat = w_meas - b_hat
    if (i >= o_sg && i < o_sg + 3) t.w_ib_b(i - o_sg) -= eps * truth.w_ib_b(i - o_sg);  // (1 + s_hat)^-1 w_meas
    if (i >= o_m && i < o_m + 3) {
      Vec3 mu = Vec3::Zero();
      mu(i - o_m) = eps;
      t.C_b_v = truth.C_b_v * C_b_n_from_euler(mu);
    }
    if (i >= o_l && i < o_l + 3) t.lever_odo_b(i - o_l) += eps;
    if (i == o_k) t.odo_scale += eps;
    return t;
  }
  double eps_for(int i) const { return i < 6 ? 1e-3 : 1e-6; }
  // The one measurement the named aid takes at `nav` (it must be due there), the covariance P = p_var I.
  Measurement measure_once(const std::string& aid, const NavState& nav, const StaticDetector& detector, double p_var) {
    const LinearizationPoint lp = lp_of(truth);
    const Eigen::MatrixXd P = Eigen::MatrixXd::Identity(layout.size(), layout.size()) * p_var;
    const Vec3 f_smooth = Vec3::Zero();
    const AidContext ctx{nav, lp, layout, opt, P, detector, f_smooth, false, 1.0, faults};
    auto updater = make_updater(aid, opt);
    EXPECT_TRUE(updater->due(ctx)) << aid;
    std::vector<Measurement> out;
    updater->measure(ctx, out);
    EXPECT_EQ(out.size(), 1u) << aid;
    return out.empty() ? Measurement() : out.front();
  }

  FilterOptions opt;
  StateLayout layout;
  AidTruth truth;
  FaultCounters faults;
};

TEST_F(AidJacobians, NonHolonomicHMatchesNumericalDerivative) {
  const Measurement m = measure_once("nhc", truth.nav, StaticDetector(0.5, 0.05, 0.01), 1.0);
  ASSERT_EQ(m.rows(), 2);
  EXPECT_EQ(m.sensor, sensors::kNonHolonomic);
  const Vec3 v_v = vehicle_velocity_model(truth);
  EXPECT_LT((m.y - v_v.tail<2>()).norm(), 1e-12);
  for (int i = 0; i < layout.size(); ++i) {
    const double eps = eps_for(i);
    const Eigen::Vector2d dy = (vehicle_velocity_model(perturbed(i, eps)).tail<2>() - v_v.tail<2>()) / eps;
    EXPECT_LT((dy - m.H.col(i)).norm(), 2e-3 * (1e-3 + m.H.col(i).norm())) << "nhc H column " << i;
  }
}

TEST_F(AidJacobians, OdometerHMatchesNumericalDerivative) {
  const LinearizationPoint lp = lp_of(truth);
  const double speed_read = 9.5;
  const OdometerObservation obs(100.0, speed_read);
  const Measurement m = obs.measurement(0, MeasurementContext{truth.nav, lp, layout, opt});
  ASSERT_EQ(m.rows(), 1);
  auto z_hat = [](const AidTruth& t) { return (1.0 + t.odo_scale) * vehicle_velocity_model(t).x(); };
  EXPECT_NEAR(m.y(0), z_hat(truth) - speed_read, 1e-12);
  for (int i = 0; i < layout.size(); ++i) {
    const double eps = eps_for(i);
    const double dy = (z_hat(perturbed(i, eps)) - z_hat(truth)) / eps;
    EXPECT_NEAR(dy, m.H(0, i), 2e-3 * (1e-3 + std::abs(m.H(0, i)))) << "odometer H column " << i;
  }
}

TEST_F(AidJacobians, ZeroAngularRateHMatchesNumericalDerivative) {
  // At a standstill the true body rate is the earth rate in body axes; the detector's window mean is what
  // the filter measures, so feed it the (perturbed) compensated rate.
  AidTruth t = truth;
  t.nav.v_n_mps.setZero();
  t.w_ib_b = t.nav.C_b_n().transpose() * earth::omega_ie_n(t.nav.pos.lat_rad) + Vec3(2e-5, -1e-5, 3e-5);
  const Vec3 f_b = t.nav.C_b_n().transpose() * Vec3(0, 0, -9.8);
  truth = t;
  StaticDetector detector(0.5, 0.05, 0.01);
  for (int k = 0; k < 100; ++k) detector.add(0.01, t.w_ib_b, f_b);
  ASSERT_TRUE(detector.is_static());
  const Measurement m = measure_once("zaru", t.nav, detector, 1e-6);
  ASSERT_EQ(m.rows(), 3);
  auto rate_model = [](const AidTruth& a) {
    return Vec3(a.w_ib_b - a.nav.C_b_n().transpose() * earth::omega_ie_n(a.nav.pos.lat_rad));
  };
  EXPECT_LT((m.y - rate_model(t)).norm(), 1e-15);
  for (int i = 0; i < layout.size(); ++i) {
    const double eps = eps_for(i);
    const Vec3 dy = (rate_model(perturbed(i, eps)) - rate_model(t)) / eps;
    // Absolute floor: the earth rate's change with latitude (1e-11 rad/s per metre) is not in H.
    EXPECT_LT((dy - m.H.col(i)).norm(), 2e-3 * m.H.col(i).norm() + 2e-11) << "zaru H column " << i;
  }
}

}  // namespace
}  // namespace ldv::est
