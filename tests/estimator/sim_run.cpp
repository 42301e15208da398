#include "sim_run.hpp"

#include <cmath>

#include "common/geo/earth_model.hpp"
#include "estimator/run/run_navigation.hpp"

namespace ldv::est::test {

Eigen::Matrix<double, 9, 1> nav_error(const NavState& s, const sim::TruthSample& t) {
  Eigen::Matrix<double, 9, 1> e;
  e.segment<3>(0) = earth::ned_between(t.pos, s.pos);
  e.segment<3>(3) = s.v_n_mps - t.vel_n_mps;
  e.segment<3>(6) = -rotvec_from_quat(Quat(s.C_b_n() * C_b_n_from_euler(t.rpy_rad).transpose()));
  return e;
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
    acc.nees_att += e.tail<3>().dot(P.block<3, 3>(6, 6).ldlt().solve(e.tail<3>()));
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

}  // namespace ldv::est::test
