#include "sim_run.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "common/geo/earth_model.hpp"
#include "estimator/filter/nav_filter.hpp"
#include "estimator/run/run_navigation.hpp"
#include "estimator/smooth/rts_recorder.hpp"

namespace ldv::est::test {

Eigen::Matrix<double, 9, 1> nav_error(const NavState& s, const sim::TruthSample& t) {
  Eigen::Matrix<double, 9, 1> e;
  e.segment<3>(0) = earth::ned_between(t.pos, s.pos);
  e.segment<3>(3) = s.v_n_mps - t.vel_n_mps;
  e.segment<3>(6) = -rotvec_from_quat(Quat(s.C_b_n() * C_b_n_from_euler(t.rpy_rad).transpose()));
  return e;
}

sim::SimRequest gyro_noise_only_request(double n_deg_per_sqrt_h, double q_rad) {
  sim::SimRequest req;
  req.seed = 7;
  req.duration_s = 360.0;
  req.scenario = "static";
  sim::ImuGrade grade;
  grade.name = "gyro-noise-only";
  grade.gyro.white_N = Vec3::Constant(n_deg_per_sqrt_h * kDegToRad / 60.0);
  if (q_rad > 0.0) grade.gyro.quantization_Q = Vec3::Constant(q_rad);
  req.custom_grade = grade;
  return req;
}

std::vector<allan::PhaseSeries> allan_channels_of(const sim::SimResult& s) {
  std::vector<allan::PhaseSeries> out;
  const double dt = 1.0 / s.request.imu_rate_hz;
  for (int sensor = 0; sensor < 2; ++sensor)
    for (int axis = 0; axis < 3; ++axis) {
      std::vector<double> y;
      y.reserve(s.imu.size());
      for (const ImuIncrement& inc : s.imu)
        y.push_back((sensor == 0 ? inc.dtheta_b_rad : inc.dvel_b_mps)(axis) / inc.dt_s);
      out.push_back(allan::phase_from_rates(std::move(y), dt,
                                            (sensor == 0 ? "gyro_" : "accel_") + std::string(1, "xyz"[axis]),
                                            sensor == 0 ? "rad/s" : "m/s^2"));
    }
  return out;
}

Accuracy evaluate(const sim::SimResult& sim, FilterOptions options, double settle_s,
                  const std::vector<ObservationPtr>& others) {
  NavFilter filter(options);
  const double t0 = sim.truth.front().t_s, dt = 1.0 / sim.request.imu_rate_hz;
  const std::vector<sim::Outage>& outages = sim.request.outages;
  Accuracy acc;
  double sh = 0, sv = 0, svel = 0, srp = 0, syaw = 0;
  long n = 0, n_nees = 0;
  double last_whole_s = -1;
  RunCallbacks cb;
  cb.on_epoch = [&](const NavFilter& f) {
    const double t = f.state().t_s;
    const size_t k = static_cast<size_t>(std::llround((t - t0) / dt));
    if (k >= sim.truth.size() || std::abs(sim.truth[k].t_s - t) > 1e-6) return;
    const auto e = nav_error(f.state(), sim.truth[k]);
    const double run_t = t - t0;
    for (const auto& o : outages) {  // the largest horizontal error while GNSS is out
      if (run_t >= o.start_s && run_t < o.start_s + o.length_s && e.head<2>().norm() > acc.outage_drift_m) {
        acc.outage_drift_m = e.head<2>().norm();
        acc.outage_drift_sigma_m = std::sqrt(std::max(0.0, f.covariance().block<2, 2>(0, 0).trace()));
      }
    }
    if (run_t < settle_s || std::floor(run_t) == last_whole_s) return;  // 1 Hz statistics
    last_whole_s = std::floor(run_t);
    bool in_outage = false;
    for (const auto& o : outages) in_outage |= run_t >= o.start_s && run_t < o.start_s + o.length_s + 10.0;
    if (in_outage) return;
    sh += e.head<2>().squaredNorm();
    sv += e(2) * e(2);
    svel += e.segment<3>(3).squaredNorm();
    srp += e.segment<2>(6).squaredNorm() / 2.0;
    syaw += e(8) * e(8);
    ++n;
    const Eigen::MatrixXd& P = f.covariance();
    acc.nees_pos += e.head<3>().dot(P.block<3, 3>(0, 0).ldlt().solve(e.head<3>()));
    acc.nees_vel += e.segment<3>(3).dot(P.block<3, 3>(3, 3).ldlt().solve(e.segment<3>(3)));
    // The reported attitude covariance: P's with the gyros' Q, which no state holds.
    const Mat3 P_att = P.block<3, 3>(6, 6) + f.attitude_quantization_cov_n();
    acc.nees_att += e.tail<3>().dot(P_att.ldlt().solve(e.tail<3>()));
    ++n_nees;
  };
  KfGinsConfig cfg = sim.kfgins;
  cfg.end_time_s = -1;
  const RunSummary sum = run_navigation(sim.imu, sim.gnss, cfg, filter, cb, nullptr, &others);
  acc.samples = n;
  acc.horiz_rms_m = std::sqrt(sh / n);
  acc.vert_rms_m = std::sqrt(sv / n);
  acc.vel_rms_mps = std::sqrt(svel / n);
  acc.roll_pitch_rms_deg = std::sqrt(srp / n) * kRadToDeg;
  acc.yaw_rms_deg = std::sqrt(syaw / n) * kRadToDeg;
  acc.nees_pos /= n_nees;
  acc.nees_vel /= n_nees;
  acc.nees_att /= n_nees;
  acc.gate_rejections = sum.faults.gate_rejections;
  return acc;
}

SmoothedRun smooth_run(const sim::SimResult& sim, const FilterOptions& options) {
  KfGinsConfig cfg = sim.kfgins;
  cfg.end_time_s = -1;
  NavFilter filter(options);
  RtsRecorder recorder(filter);
  filter.set_observer(&recorder);
  RunCallbacks cb;
  cb.on_epoch = [&](const NavFilter& f) { recorder.add_row(f, 0); };
  run_navigation(sim.imu, sim.gnss, cfg, filter, cb);
  return recorder.smooth();
}

SmoothedDrive smooth_drive(const std::string& grade, std::uint64_t seed, const std::vector<sim::Outage>& outages,
                           double duration_s) {
  sim::SimRequest req;
  req.grade = grade;
  req.seed = seed;
  req.duration_s = duration_s;
  req.scenario = "figure8";
  req.outages = outages;
  const sim::SimResult sim = sim::simulate(req);
  FilterOptions opt = options_from_kfgins(sim.kfgins);
  // The simulator's RTK errors have a 60 s Gauss-Markov part: modelled, as a consistency check needs.
  opt.add.push_back("gnss_position_bias");
  const SmoothedRun run = smooth_run(sim, opt);

  SmoothedDrive d;
  d.gaps.resize(outages.size());
  const double t0 = sim.truth.front().t_s, dt = 1.0 / req.imu_rate_hz;
  double sf = 0, ss = 0, in_aided = 0, in_gaps = 0, nees_aided = 0, nees_gaps = 0, forward_nees_gaps = 0;
  long n_aided = 0, n_gaps = 0;
  for (std::size_t i = 0; i < run.size(); i += 20) {  // 10 Hz
    const SmoothedRow row = run.row(i);
    const double t = row.forward.t_s;
    const size_t k = static_cast<size_t>(std::llround((t - t0) / dt));
    if (k >= sim.truth.size() || std::abs(sim.truth[k].t_s - t) > 1e-6) continue;
    const auto ef = nav_error(row.forward, sim.truth[k]);
    const auto es = nav_error(row.smoothed, sim.truth[k]);
    const double run_t = t - t0;
    int gap = -1;
    for (std::size_t g = 0; g < outages.size(); ++g)
      if (run_t >= outages[g].start_s && run_t < outages[g].start_s + outages[g].length_s) gap = static_cast<int>(g);
    const Eigen::Matrix<double, 9, 1> z = es.cwiseQuotient(row.std_smoothed);
    const double within = (z.array().abs() <= 3.0).cast<double>().mean();
    if (gap >= 0) {
      GapErrors& ge = d.gaps[gap];
      ge.forward_end_m = ef.head<2>().norm();  // the last sample inside the gap stays
      ge.smoothed_max_m = std::max(ge.smoothed_max_m, es.head<2>().norm());
      in_gaps += within;
      nees_gaps += z.squaredNorm() / 9.0;
      forward_nees_gaps += ef.cwiseQuotient(row.std_forward).squaredNorm() / 9.0;
      ++n_gaps;
    } else if (run_t > 30.0) {
      sf += ef.head<2>().squaredNorm();
      ss += es.head<2>().squaredNorm();
      in_aided += within;
      nees_aided += z.squaredNorm() / 9.0;
      ++n_aided;
    }
  }
  for (const GapErrors& g : d.gaps) EXPECT_GT(g.forward_end_m, 0.0) << "a gap with no sample compared";
  d.forward_aided_rms_m = std::sqrt(sf / n_aided);
  d.smoothed_aided_rms_m = std::sqrt(ss / n_aided);
  d.within_3sigma_aided = in_aided / n_aided;
  d.within_3sigma_gaps = in_gaps / n_gaps;
  d.nees_per_dof_aided = nees_aided / n_aided;
  d.nees_per_dof_gaps = nees_gaps / n_gaps;
  d.forward_nees_per_dof_gaps = forward_nees_gaps / n_gaps;
  for (std::size_t g = 0; g < d.gaps.size(); ++g)
    std::printf("%s seed %llu gap %zu (%.0f s): forward drift at the end %.3f m, smoothed max inside %.3f m\n",
                grade.c_str(), static_cast<unsigned long long>(seed), g, outages[g].length_s, d.gaps[g].forward_end_m,
                d.gaps[g].smoothed_max_m);
  std::printf("  aided horizontal RMS forward %.4f m, smoothed %.4f m; smoothed within 3 sigma: aided %.4f, gaps %.4f; "
              "NEES per dof: aided %.2f, gaps %.2f (forward %.2f)\n",
              d.forward_aided_rms_m, d.smoothed_aided_rms_m, d.within_3sigma_aided, d.within_3sigma_gaps,
              d.nees_per_dof_aided, d.nees_per_dof_gaps, d.forward_nees_per_dof_gaps);
  return d;
}

void expect_smoothed_consistent(const SmoothedDrive& d) {
  EXPECT_LE(d.smoothed_aided_rms_m, d.forward_aided_rms_m);
  // Consistent: 3 sigma holds the error (99.7 % of a Gaussian; time-correlated samples, so 97 %), the
  // normalised squared error is not above 1 by much (not overconfident), and not below the forward filter's by
  // much: the smoother is as honest as the model it smooths (the simulator's configuration for a grade is
  // pessimistic in free inertial, most of all vertically: the forward NEES per dof in the gaps is mostly 0.1-0.6;
  // where the forward filter is overconfident, the smoother is held to 1/3).
  EXPECT_GE(d.within_3sigma_aided, 0.97);
  EXPECT_GE(d.within_3sigma_gaps, 0.97);
  EXPECT_GT(d.nees_per_dof_aided, 0.2);
  EXPECT_LT(d.nees_per_dof_aided, 2.0);
  EXPECT_GT(d.nees_per_dof_gaps, std::min(d.forward_nees_per_dof_gaps, 1.0) / 3.0);
  EXPECT_LT(d.nees_per_dof_gaps, 2.0);
}

void expect_smoothing_works(const SmoothedDrive& d, double max_ratio) {
  for (const GapErrors& g : d.gaps) EXPECT_LE(g.smoothed_max_m, max_ratio * g.forward_end_m);
  expect_smoothed_consistent(d);
}

}  // namespace ldv::est::test
