// Every analytic Jacobian against a numerical derivative of the nonlinear model written here,
// independently of the estimator code: the navigation error dynamics F, each effect block's sensor
// Jacobians, and the H of GNSS position / velocity (lever arm, time offset, gyro effects).
#include <gtest/gtest.h>

#include "common/geo/earth_model.hpp"
#include "estimator/effects/registry.hpp"
#include "estimator/filter/nav_error_dynamics.hpp"
#include "estimator/options.hpp"
#include "estimator/state/state_layout.hpp"
#include "estimator/update/gnss_position.hpp"
#include "estimator/update/gnss_velocity.hpp"

namespace ldv::est {
namespace {

// ---- the nonlinear continuous-time INS model ------------------------------------------------------
struct Truth {
  Vec3 lla;  // lat, lon [rad], h [m]
  Vec3 v_n;
  Mat3 C_b_n;
};

Truth derivative(const Truth& x, const Vec3& w_ib_b, const Vec3& f_b) {
  const earth::Radii r = earth::radii(x.lla.x());
  const double Rm = r.meridian_m + x.lla.z(), Rn = r.prime_vertical_m + x.lla.z();
  const Vec3 w_ie = earth::omega_ie_n(x.lla.x());
  const Vec3 w_en = earth::omega_en_n(x.lla.x(), x.lla.z(), x.v_n);
  Truth d;
  d.lla = Vec3(x.v_n.x() / Rm, x.v_n.y() / (Rn * std::cos(x.lla.x())), -x.v_n.z());
  d.v_n = x.C_b_n * f_b + earth::gravity_n(x.lla.x(), x.lla.z()) - (2.0 * w_ie + w_en).cross(x.v_n);
  d.C_b_n = x.C_b_n * skew(w_ib_b) - skew(w_ie + w_en) * x.C_b_n;
  return d;
}

Truth step(const Truth& x, const Truth& d, double h) { return {x.lla + d.lla * h, x.v_n + d.v_n * h, x.C_b_n + d.C_b_n * h}; }

// Error-state definition: delta_r NED metres, delta_v, C_hat = exp(-[phi x]) C.
Eigen::Matrix<double, 9, 1> error_of(const Truth& est, const Truth& tru) {
  const earth::Radii r = earth::radii(tru.lla.x());
  Eigen::Matrix<double, 9, 1> e;
  const Vec3 d = est.lla - tru.lla;
  e.segment<3>(0) = Vec3(d.x() * (r.meridian_m + tru.lla.z()),
                         d.y() * (r.prime_vertical_m + tru.lla.z()) * std::cos(tru.lla.x()), -d.z());
  e.segment<3>(3) = est.v_n - tru.v_n;
  const Eigen::JacobiSVD<Mat3> svd(est.C_b_n * tru.C_b_n.transpose(), Eigen::ComputeFullU | Eigen::ComputeFullV);
  e.segment<3>(6) = -rotvec_from_quat(Quat(Mat3(svd.matrixU() * svd.matrixV().transpose())));
  return e;
}

Truth perturbed(const Truth& x, const Eigen::Matrix<double, 9, 1>& e) {
  const earth::Radii r = earth::radii(x.lla.x());
  Truth y = x;
  y.lla += Vec3(e(0) / (r.meridian_m + x.lla.z()), e(1) / ((r.prime_vertical_m + x.lla.z()) * std::cos(x.lla.x())), -e(2));
  y.v_n += e.segment<3>(3);
  y.C_b_n = quat_from_rotvec(-e.segment<3>(6)).toRotationMatrix() * x.C_b_n;
  return y;
}

TEST(Jacobians, NavigationErrorDynamicsMatchNumericalDerivative) {
  // Given a fast, turning, climbing vehicle at 50 deg latitude
  const Truth x{Vec3(50.0 * kDegToRad, 8.0 * kDegToRad, 400.0), Vec3(25.0, -18.0, 1.5),
                C_b_n_from_euler(Vec3(0.2, -0.1, 2.0))};
  const Vec3 w_ib_b(0.05, -0.02, 0.3), f_b(1.5, -2.0, -9.6);
  // When each error state is perturbed and the error's rate of change is differenced numerically
  // Position rows: a long step keeps differences of latitudes (~0.9 rad) far above double precision
  // (positions are linear in time to first order); velocity and attitude rows: a short step, so the
  // rotation over the step (w h) does not bias the difference.
  const double eps[9] = {100, 100, 100, 0.1, 0.1, 0.1, 1e-4, 1e-4, 1e-4};
  Mat9 F_num;
  for (int k = 0; k < 18; ++k) {
    const int i = k % 9;
    const double h = k < 9 ? 0.5 : 1e-3;
    Eigen::Matrix<double, 9, 1> e = Eigen::Matrix<double, 9, 1>::Zero();
    e(i) = eps[i];
    const Truth xe = perturbed(x, e);
    const Truth dx = derivative(x, w_ib_b, f_b), dxe = derivative(xe, w_ib_b, f_b);
    const auto ep = error_of(step(xe, dxe, h), step(x, dx, h));
    const auto em = error_of(step(xe, dxe, -h), step(x, dx, -h));
    const Eigen::Matrix<double, 9, 1> col = (ep - em) / (2.0 * h) / eps[i];
    if (k < 9) F_num.block<3, 1>(0, i) = col.head<3>();
    else F_num.block<6, 1>(3, i) = col.tail<6>();
  }
  // Then the analytic F agrees (gravity gradients from GeographicLib by central differences)
  NavState s;
  s.pos = {x.lla.x(), x.lla.y(), x.lla.z()};
  s.v_n_mps = x.v_n;
  s.q_b_n = Quat(x.C_b_n);
  const Vec3 dg_dlat = (earth::gravity_n(x.lla.x() + 1e-5, x.lla.z()) - earth::gravity_n(x.lla.x() - 1e-5, x.lla.z())) / 2e-5;
  const Vec3 dg_dh = (earth::gravity_n(x.lla.x(), x.lla.z() + 1.0) - earth::gravity_n(x.lla.x(), x.lla.z() - 1.0)) / 2.0;
  const Mat9 F = nav_error_F(s, x.C_b_n * f_b, dg_dlat, dg_dh);
  for (int r = 0; r < 9; ++r)
    for (int c = 0; c < 9; ++c)
      EXPECT_NEAR(F(r, c), F_num(r, c), 2e-3 * std::abs(F_num(r, c)) + 2e-9) << "F(" << r << "," << c << ")";
}

// ---- sensor model of docs/effects.md, written independently of ImuErrorModel::correct --------------
struct SensorTruth {
  Vec3 bg = Vec3::Zero(), ba = Vec3::Zero(), sg = Vec3::Zero(), sa = Vec3::Zero(), mg = Vec3::Zero(),
       ma = Vec3::Zero(), k = Vec3::Zero();
};
Mat3 N(const Vec3& m) {
  Mat3 n;
  n << 0, m.z(), m.y(), m.z(), 0, m.x(), m.y(), m.x(), 0;
  return n;
}
void sense(const SensorTruth& e, const Vec3& w, const Vec3& f, Vec3& w_meas, Vec3& f_meas) {
  w_meas = (Mat3::Identity() + Mat3(e.sg.asDiagonal()) + N(e.mg)) * w + e.bg + e.k.cwiseProduct(f);
  f_meas = (Mat3::Identity() + Mat3(e.sa.asDiagonal()) + N(e.ma)) * f + e.ba;
}

TEST(Jacobians, EveryEffectBlockSensorJacobianMatchesNumericalDerivative) {
  FilterOptions opt;
  const std::vector<std::string> all = {"gyro_bias", "accel_bias", "gyro_scale", "accel_scale",
                                        "gyro_misalignment", "accel_misalignment", "g_sensitivity",
                                        "gyro_moving_bias", "accel_moving_bias"};
  const StateLayout layout(all, opt);
  const int m = layout.effect_dim();
  // Given true sensor errors and a true motion
  SensorTruth tru;
  tru.bg = Vec3(1e-4, -2e-4, 3e-5);
  tru.ba = Vec3(0.01, -0.02, 0.03);
  tru.sg = Vec3(300e-6, -200e-6, 500e-6);
  tru.sa = Vec3(-100e-6, 400e-6, 250e-6);
  tru.mg = Vec3(50e-6, -80e-6, 30e-6);
  tru.ma = Vec3(-60e-6, 20e-6, 90e-6);
  tru.k = Vec3(1e-5, -2e-5, 3e-5);
  const Vec3 w(0.3, -0.5, 0.8), f(2.0, -1.0, -9.5);
  Vec3 w_meas, f_meas;
  sense(tru, w, f, w_meas, f_meas);
  // The estimate vector that reproduces the truth (moving bias: only the constant component).
  Eigen::VectorXd x_true = Eigen::VectorXd::Zero(m);
  auto set = [&](const char* name, const Vec3& v) { x_true.segment<3>(layout.find(name)->offset - kNavDim) = v; };
  set("gyro_bias", tru.bg / 2);
  set("accel_bias", tru.ba / 2);
  set("gyro_moving_bias", tru.bg / 2);
  set("accel_moving_bias", tru.ba / 2);
  set("gyro_scale", tru.sg);
  set("accel_scale", tru.sa);
  set("gyro_misalignment", tru.mg);
  set("accel_misalignment", tru.ma);
  set("g_sensitivity", tru.k);
  auto compensate = [&](const Eigen::VectorXd& x, Vec3& w_hat, Vec3& f_hat) {
    ImuErrorModel model;
    for (const auto& b : layout.blocks()) b.effect->apply(x.segment(b.offset - kNavDim, b.dim), model);
    ImuIncrement raw;
    raw.dt_s = 1.0;
    raw.dtheta_b_rad = w_meas;
    raw.dvel_b_mps = f_meas;
    const ImuIncrement c = model.correct(raw);
    w_hat = c.dtheta_b_rad;
    f_hat = c.dvel_b_mps;
  };
  Vec3 w0, f0;
  compensate(x_true, w0, f0);
  ASSERT_LT((w0 - w).norm(), 1e-12);  // correct() inverts the documented sensor model
  ASSERT_LT((f0 - f).norm(), 1e-12);
  LinearizationPoint lp;
  lp.omega_ib_b_rad_s = w;
  lp.f_b_mps2 = f;
  // The Jacobians are first order in the sensor errors: products of two errors (largest here 5e-4,
  // e.g. scale x bias) are neglected, so agreement is expected to 2x that, relative.
  const double kFirstOrder = 1e-3;
  for (const auto& b : layout.blocks()) {
    Mat3X Jg = Mat3X::Zero(3, b.dim), Ja = Mat3X::Zero(3, b.dim);
    b.effect->imu_jacobians(lp, Jg, Ja);
    for (int i = 0; i < b.dim; ++i) {
      // When one estimated state is off by eps (delta_x = estimate - truth)
      const double eps = 1e-7;
      Eigen::VectorXd x = x_true;
      x(b.offset - kNavDim + i) += eps;
      Vec3 wh, fh;
      compensate(x, wh, fh);
      // Then the compensated sensor error changes as the block's Jacobian says
      EXPECT_LT(((wh - w) / eps - Jg.col(i)).norm(), kFirstOrder * (1.0 + Jg.col(i).norm())) << b.effect->name() << " gyro " << i;
      EXPECT_LT(((fh - f) / eps - Ja.col(i)).norm(), kFirstOrder * (1.0 + Ja.col(i).norm())) << b.effect->name() << " accel " << i;
    }
  }
}

// ---- GNSS measurement models ------------------------------------------------------------------------
Geodetic antenna_position(const NavState& s, const Vec3& lever_b) {
  const Vec3 r_e = earth::ecef_from_geodetic(s.pos) + earth::C_n_e(s.pos) * s.C_b_n() * lever_b;
  return earth::geodetic_from_ecef(r_e);
}

NavState perturbed_nav(const NavState& s, const Eigen::Matrix<double, 9, 1>& e) {
  NavState y = s;
  y.pos = earth::offset_ned(s.pos, e.segment<3>(0));
  y.v_n_mps += e.segment<3>(3);
  y.q_b_n = quat_from_rotvec(-e.segment<3>(6)) * s.q_b_n;
  return y;
}

TEST(Jacobians, GnssPositionAndVelocityHMatchNumericalDerivative) {
  FilterOptions opt;
  opt.lever_arm.init = Vec3(1.2, -0.4, -1.6);
  const StateLayout layout({"gyro_bias", "gyro_scale", "lever_arm", "time_offset"}, opt);
  NavState s;
  s.pos = {31.0 * kDegToRad, 114.0 * kDegToRad, 30.0};
  s.v_n_mps = Vec3(8.0, 6.0, -0.3);
  s.q_b_n = quat_from_euler(Vec3(0.05, -0.03, 0.9));
  const Vec3 w_true(0.02, -0.03, 0.4), a_n(0.5, -0.8, 0.05);
  const Vec3 lever = opt.lever_arm.init;

  auto lp_for = [&](const NavState& st, const Vec3& w, const Vec3& l) {
    LinearizationPoint lp;
    lp.C_b_n = st.C_b_n();
    lp.omega_ib_b_rad_s = w;
    lp.lever_arm_b_m = l;
    lp.a_n_mps2 = a_n;
    lp.omega_in_n_rad_s = earth::omega_ie_n(st.pos.lat_rad) + earth::omega_en_n(st.pos.lat_rad, st.pos.h_m, st.v_n_mps);
    lp.v_ant_n_mps = antenna_velocity_n(st, lp);
    return lp;
  };
  // The truth fix: antenna position and velocity (independent ECEF route for the position).
  const LinearizationPoint lp0 = lp_for(s, w_true, lever);
  GnssFix fix;
  fix.pos = antenna_position(s, lever);
  fix.vel_n_mps = s.v_n_mps + s.C_b_n() * w_true.cross(lever) - lp0.omega_in_n_rad_s.cross(s.C_b_n() * lever);
  fix.has_velocity = true;
  const Measurement hp = gnss_position_measurement(s, lp0, layout, fix);
  const Measurement hv = gnss_velocity_measurement(s, lp0, layout, fix);
  EXPECT_LT(hp.y.norm(), 1e-6);
  EXPECT_LT(hv.y.norm(), 1e-9);

  const int n = layout.size();
  const int o_bg = layout.find("gyro_bias")->offset, o_sg = layout.find("gyro_scale")->offset;
  const int o_l = layout.find("lever_arm")->offset, o_t = layout.find("time_offset")->offset;
  for (int i = 0; i < n; ++i) {
    const double eps = i < 6 ? 1e-3 : (i < 9 ? 1e-6 : 1e-5);
    Eigen::Matrix<double, 9, 1> e = Eigen::Matrix<double, 9, 1>::Zero();
    if (i < 9) e(i) = eps;
    NavState se = perturbed_nav(s, e);
    Vec3 w_hat = w_true, l_hat = lever;
    GnssFix fe = fix;
    if (i >= o_bg && i < o_bg + 3) w_hat(i - o_bg) -= eps;                  // w_hat = w_meas - b_hat
    if (i >= o_sg && i < o_sg + 3) w_hat(i - o_sg) -= eps * w_true(i - o_sg);  // (1 + s_hat)^-1 w_meas
    if (i >= o_l && i < o_l + 3) l_hat(i - o_l) += eps;
    if (i == o_t) {
      // tau_hat = tau + eps: the fix was really taken eps later than where the filter applies it.
      const Vec3 v_ant = fix.vel_n_mps;
      fe.pos = earth::offset_ned(fix.pos, v_ant * eps);
      fe.vel_n_mps = fix.vel_n_mps + a_n * eps;
    }
    const Geodetic ant = antenna_position(se, l_hat);
    const Vec3 yp = earth::ned_between(fe.pos, ant);
    const LinearizationPoint lpe = lp_for(se, w_hat, l_hat);
    const Vec3 yv = se.v_n_mps + se.C_b_n() * w_hat.cross(l_hat) - lpe.omega_in_n_rad_s.cross(se.C_b_n() * l_hat) - fe.vel_n_mps;
    EXPECT_LT((yp / eps - hp.H.col(i)).norm(), 2e-3 * (1.0 + hp.H.col(i).norm())) << "position H column " << i;
    EXPECT_LT((yv / eps - hv.H.col(i)).norm(), 2e-3 * (1e-3 + hv.H.col(i).norm())) << "velocity H column " << i;
  }
}

}  // namespace
}  // namespace ldv::est
