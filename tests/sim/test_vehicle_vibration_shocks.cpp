// Vibration and road shocks (sim/vehicle_vibration.hpp, sim/road_shocks.hpp) measured from the increments
// against their definitions: the white part's variance and Allan deviation against factor x the grade's
// ARW / VRW, the engine harmonic against the exact integral of a sinusoid (and its alias), zero mean in
// the navigation frame, and each bump against a strapdown integration that must return to the truth.
#include <gtest/gtest.h>

#include "sim/road_shocks.hpp"
#include "sim_test_helpers.hpp"

using namespace ldv;
using namespace ldv::sim;
using namespace ldv::sim::test;

namespace {
constexpr double kDegPerSqrtH = kDegToRad / 60.0;

// A grade with white noise only (hg1700-typical's ARW and VRW), so the increments' spread is white noise alone.
ImuGrade white_only_grade() {
  ImuGrade g;
  g.name = "white-only";
  g.source = "test";
  g.gyro.white_N = Vec3::Constant(0.125 * kDegPerSqrtH);
  g.accel.white_N = Vec3::Constant(0.0296 / 60.0);
  return g;
}

SimRequest vibration_request(const std::string& scenario, double duration_s, double rate_hz, bool noise) {
  SimRequest q = perfect_request(scenario, duration_s, rate_hz);
  q.custom_grade = white_only_grade();
  q.with_noise = noise;
  q.vehicle.vibration_factor = 10.0;
  q.vehicle.engine_accel_mps2 = 0.0;  // white part alone
  q.vehicle.engine_gyro_dps = 0.0;
  return q;
}

// Variance per sample of (measured - exact) increments, pooled over the three axes, divided by N^2 dt.
struct WhiteRatio {
  double gyro, accel;
};
WhiteRatio white_variance_ratio(const SimResult& r, const SimResult& exact) {
  const double dt = r.imu.front().dt_s;
  const Vec3 Ng = white_only_grade().gyro.white_N, Na = white_only_grade().accel.white_N;
  double sg = 0, sa = 0;
  for (size_t k = 0; k < r.imu.size(); ++k) {
    sg += (r.imu[k].dtheta_b_rad - exact.imu[k].dtheta_b_rad).cwiseQuotient(Ng).squaredNorm();
    sa += (r.imu[k].dvel_b_mps - exact.imu[k].dvel_b_mps).cwiseQuotient(Na).squaredNorm();
  }
  const double n = 3.0 * r.imu.size();
  return {sg / n / dt, sa / n / dt};
}

// Least-squares amplitude of a sinusoid of frequency f [Hz] in y_k (sampled at t_k = k dt), and the rms of
// what the sinusoid leaves.
struct SineFit {
  double amplitude, residual_rms;
};
SineFit fit_sine(const std::vector<double>& y, double dt, double f) {
  double cc = 0, ss = 0, cs = 0, cy = 0, sy = 0;
  for (size_t k = 0; k < y.size(); ++k) {
    const double c = std::cos(2 * kPi * f * k * dt), s = std::sin(2 * kPi * f * k * dt);
    cc += c * c, ss += s * s, cs += c * s, cy += c * y[k], sy += s * y[k];
  }
  const double det = cc * ss - cs * cs, a = (cy * ss - sy * cs) / det, b = (sy * cc - cy * cs) / det;
  double res = 0;
  for (size_t k = 0; k < y.size(); ++k) {
    const double e = y[k] - a * std::cos(2 * kPi * f * k * dt) - b * std::sin(2 * kPi * f * k * dt);
    res += e * e;
  }
  return {std::hypot(a, b), std::sqrt(res / y.size())};
}

const std::string kFastStraight = R"(name: fast_straight
start: {lat_deg: 32.88, lon_deg: -117.23, h_m: 100, yaw_deg: 15, speed_mps: 30}
segments:
  - {type: straight, duration_s: 40}
)";

Mat3 exp_so3(const Vec3& phi) {
  return Mat3(Eigen::AngleAxisd(phi.norm(), phi.norm() > 0 ? Vec3(phi.normalized()) : Vec3::UnitX()));
}
}  // namespace

TEST(SimVibration, WhitePartMakesTheInstalledNoiseFactorTimesTheGradesArwAndVrw) {
  // Given a white-noise-only IMU standing still, with and without --vibration 10
  SimRequest q = vibration_request("static", 100.0, 100.0, true);
  const SimResult with = simulate(q);
  q.vehicle.vibration_factor.reset();
  const SimResult without = simulate(q);
  SimRequest e = perfect_request("static", 100.0, 100.0);
  const SimResult exact = simulate(e);
  // Then the variance per sample is factor^2 N^2 dt (30000 samples per triad: 0.8 % std of the estimate)
  const WhiteRatio w = white_variance_ratio(with, exact), o = white_variance_ratio(without, exact);
  EXPECT_NEAR(w.gyro, 100.0, 3.0);
  EXPECT_NEAR(w.accel, 100.0, 3.0);
  EXPECT_NEAR(o.gyro, 1.0, 0.03);  // the measurement itself: the datasheet's noise without vibration
  EXPECT_NEAR(o.accel, 1.0, 0.03);
  // and the Allan deviation at tau = 1 s is factor x ARW (100 clusters x 3 axes: ~4 % std).
  double avar = 0;
  int terms = 0;
  for (int i = 0; i < 3; ++i) {
    std::vector<double> mean_rate;
    for (size_t c = 0; c + 100 <= with.imu.size(); c += 100) {
      double s = 0;
      for (size_t k = c; k < c + 100; ++k) s += with.imu[k].dtheta_b_rad[i] - exact.imu[k].dtheta_b_rad[i];
      mean_rate.push_back(s / 1.0);
    }
    for (size_t c = 1; c < mean_rate.size(); ++c, ++terms) avar += 0.5 * std::pow(mean_rate[c] - mean_rate[c - 1], 2);
  }
  EXPECT_NEAR(std::sqrt(avar / terms) / (10.0 * 0.125 * kDegPerSqrtH), 1.0, 0.12);
  // The answer key says so.
  EXPECT_NEAR(with.injected_effects.at("installed_arw")[0], 10.0 * 0.125 * kDegPerSqrtH, 1e-15);
  EXPECT_DOUBLE_EQ(with.injected_effects.at("vibration_white_factor")[0], 10.0);
}

TEST(SimVibration, WithoutNoiseOnlyTheVibrationsShareRemains) {
  // --no-noise removes the grade's white noise; the vibration (an injected effect) adds N sqrt(F^2 - 1).
  const SimResult r = simulate(vibration_request("static", 100.0, 100.0, false));
  const SimResult exact = simulate(perfect_request("static", 100.0, 100.0));
  const WhiteRatio w = white_variance_ratio(r, exact);
  EXPECT_NEAR(w.gyro, 99.0, 3.0);
  EXPECT_NEAR(w.accel, 99.0, 3.0);
}

TEST(SimVibration, EngineHarmonicIsTheExactIntegralOfASinusoidAliasedByTheImuRate) {
  const double dt = 0.01, A = 0.3, G = 0.2 * kDegToRad;
  struct Case {
    std::string scenario;
    double engine_hz, seen_hz;  // idle 25 Hz standing; 70 Hz at 30 m/s, seen at 100 - 70 = 30 Hz
  };
  const std::string fast = write_text("fast_straight.yaml", kFastStraight);
  for (const Case& c : {Case{"static", 25.0, 25.0}, Case{fast, 70.0, 30.0}}) {
    SimRequest q = perfect_request(c.scenario, 30.0, 1.0 / dt);
    q.vehicle.vibration_factor = 1.0;  // the harmonic alone (the perfect grade has no white noise)
    const SimResult with = simulate(q);
    const SimResult exact = simulate(perfect_request(c.scenario, 30.0, 1.0 / dt));
    std::vector<double> az, gx;
    for (size_t k = 200; k < with.imu.size(); ++k) {  // after the 1 s ramp-up
      az.push_back(with.imu[k].dvel_b_mps.z() - exact.imu[k].dvel_b_mps.z());
      gx.push_back(with.imu[k].dtheta_b_rad.x() - exact.imu[k].dtheta_b_rad.x());
    }
    // Then each increment is int A sin(w t + p) dt over the interval: a sampled sinusoid of amplitude
    // 2 A / w sin(w dt / 2) at the aliased frequency (point sampling would give A dt).
    const double w = 2 * kPi * c.engine_hz, gain = 2.0 / w * std::sin(w * dt / 2);
    const SineFit fa = fit_sine(az, dt, c.seen_hz), fg = fit_sine(gx, dt, c.seen_hz);
    EXPECT_NEAR(fa.amplitude, A * gain, 1e-12 * A) << c.scenario;
    EXPECT_LT(fa.residual_rms, 1e-13) << c.scenario;
    EXPECT_NEAR(fg.amplitude, G * gain, 1e-12 * G) << c.scenario;
    EXPECT_LT(fg.residual_rms, 1e-15) << c.scenario;
  }
}

TEST(SimVibration, EngineHarmonicHasZeroMeanInTheNavigationFrame) {
  // Given the harmonic alone over a drive (speed and so frequency changing, turns rotating the body)
  SimRequest q = perfect_request("drive", 200.0, 200.0);
  q.vehicle.vibration_factor = 1.0;
  const SimResult with = simulate(q);
  const SimResult exact = simulate(perfect_request("drive", 200.0, 200.0));
  // When the vibration's increments are rotated into NED with the true attitude and summed (the velocity
  // error it would cause a strapdown INS) and summed again (the position error)
  Vec3 dv_n = Vec3::Zero(), dp_n = Vec3::Zero(), mean_dv = Vec3::Zero();
  double worst_dv = 0;
  for (size_t k = 0; k < with.imu.size(); ++k) {
    const Mat3 C = C_b_n_from_euler(with.truth[k + 1].rpy_rad);
    dv_n += C * (with.imu[k].dvel_b_mps - exact.imu[k].dvel_b_mps);
    dp_n += dv_n * 0.005;
    mean_dv += dv_n;
    worst_dv = std::max(worst_dv, dv_n.norm());
  }
  mean_dv /= static_cast<double>(with.imu.size());
  // Then the velocity error stays within the harmonic's velocity amplitude (A / w at idle: 1.9 mm/s) and
  // averages to zero: no drift of the position (a constant 1.9 mm/s would give 0.38 m here).
  const double bound = 0.3 / (2 * kPi * 25.0);
  EXPECT_LT(worst_dv, 1.2 * bound);
  EXPECT_GT(worst_dv, 0.5 * bound);  // it is there
  EXPECT_LT(mean_dv.norm(), 0.05 * bound);
  EXPECT_LT(dp_n.norm(), 0.01);
}

TEST(SimShocks, BumpsComeAtTheRatePerKmWhileMovingOnly) {
  SimRequest q = perfect_request("drive", 300.0, 100.0);
  q.vehicle.shocks_per_km = 40.0;
  const SimResult r = simulate(q);
  double km = 0;
  for (size_t k = 1; k < r.truth.size(); ++k)
    km += 0.5 * (r.truth[k].vel_n_mps.norm() + r.truth[k - 1].vel_n_mps.norm()) * 0.01 / 1000.0;
  // Poisson: 40/km over ~4 km is ~160 bumps, std ~13; allow 4 std.
  const double expected = 40.0 * km;
  EXPECT_NEAR(static_cast<double>(r.shocks.size()), expected, 4.0 * std::sqrt(expected)) << km << " km";
  EXPECT_EQ(r.injected_effects.at("shocks.count")[0], static_cast<double>(r.shocks.size()));
  for (const ShockEvent& e : r.shocks) {
    const size_t k = static_cast<size_t>(e.t_start_s / 0.01);
    EXPECT_GT(r.truth[k + 1].vel_n_mps.norm(), 0.01) << "a bump while standing at " << e.t_start_s;
    EXPECT_GE(e.duration_s, 0.1);
    EXPECT_LE(e.duration_s, 0.3);
    EXPECT_LE(std::abs(e.pitch_rate_peak_rad_s), 40.0 * kDegToRad);
    EXPECT_GE(std::abs(e.pitch_rate_peak_rad_s), 10.0 * kDegToRad);
    EXPECT_LE(std::abs(e.vertical_accel_peak_mps2), 4.0);
  }
}

TEST(SimShocks, EachBumpPeaksAsDrawnAndAStrapdownReturnsToTheTruthAfterIt) {
  const double dt = 0.005;
  SimRequest q = perfect_request("drive", 200.0, 1.0 / dt);
  q.vehicle.shocks_per_km = 10.0;
  const SimResult with = simulate(q);
  const SimResult exact = simulate(perfect_request("drive", 200.0, 1.0 / dt));
  ASSERT_GE(with.shocks.size(), 10u);
  int checked = 0;
  for (size_t i = 0; i < with.shocks.size(); ++i) {
    const ShockEvent& e = with.shocks[i];
    const double t_begin = e.t_start_s - 0.05, t_end = e.t_start_s + e.duration_s + 0.05;
    const bool alone = (i == 0 || with.shocks[i - 1].t_start_s + with.shocks[i - 1].duration_s < t_begin) &&
                       (i + 1 == with.shocks.size() || with.shocks[i + 1].t_start_s > t_end);
    if (!alone) continue;
    // Given the same strapdown (attitude by rotation vectors, velocity by the mid-interval attitude) over
    // the bump on the increments with and without it, from the true attitude
    const size_t k0 = static_cast<size_t>(t_begin / dt), k1 = static_cast<size_t>(t_end / dt);
    Mat3 Cw = C_b_n_from_euler(with.truth[k0].rpy_rad), Ce = Cw;
    Vec3 vw = Vec3::Zero(), ve = Vec3::Zero();
    double peak_angle = 0, worst_rate = 0, worst_accel = 0;
    // The bump's closed form (sim/road_shocks.hpp): angle and heave velocity (peak / w) e^{-s/tau} sin(w s).
    const double w = 3 * kPi / e.duration_s, tau = e.duration_s / 3;
    auto shape = [&](double t) {
      const double s = t - e.t_start_s;
      return s <= 0 || s >= e.duration_s ? 0.0 : std::exp(-s / tau) * std::sin(w * s) / w;
    };
    for (size_t k = k0; k < k1; ++k) {
      const ImuIncrement &a = with.imu[k], &b = exact.imu[k];
      vw += Cw * exp_so3(0.5 * a.dtheta_b_rad) * a.dvel_b_mps;
      ve += Ce * exp_so3(0.5 * b.dtheta_b_rad) * b.dvel_b_mps;
      Cw = Cw * exp_so3(a.dtheta_b_rad);
      Ce = Ce * exp_so3(b.dtheta_b_rad);
      const double d_shape = shape((k + 1) * dt) - shape(k * dt);
      worst_rate =
          std::max(worst_rate, std::abs(a.dtheta_b_rad.y() - b.dtheta_b_rad.y() - e.pitch_rate_peak_rad_s * d_shape));
      worst_accel =
          std::max(worst_accel, std::abs(a.dvel_b_mps.z() - b.dvel_b_mps.z() - e.vertical_accel_peak_mps2 * d_shape));
      peak_angle = std::max(peak_angle, Eigen::AngleAxisd(Ce.transpose() * Cw).angle());
    }
    // Then each increment differs by the closed form's change over the interval (up to the first-order
    // rotation of the true rate and specific force by the bump's angle: < 0.5 % and 2 % of a peak increment),
    EXPECT_LT(worst_rate, 0.005 * std::abs(e.pitch_rate_peak_rad_s) * dt) << e.t_start_s;
    EXPECT_LT(worst_accel, 0.02 * std::abs(e.vertical_accel_peak_mps2) * dt) << e.t_start_s;
    // the body really turned during the bump (peak angle ~ rate / omega),
    EXPECT_GT(peak_angle, 0.5 * std::abs(e.pitch_rate_peak_rad_s) / e.omega_rad_s());
    // and after it the strapdown is back on the smooth truth: attitude and velocity within second-order
    // terms of the < 0.025 rad excursion (without the rotation of the specific force by the bump's angle the
    // velocity would be off by g * integral(angle) ~ 5e-3 m/s).
    EXPECT_LT(Eigen::AngleAxisd(Ce.transpose() * Cw).angle(), 5e-6) << e.t_start_s;
    EXPECT_LT((vw - ve).norm(), 5e-4) << e.t_start_s;
    ++checked;
  }
  EXPECT_GE(checked, 5);
}
