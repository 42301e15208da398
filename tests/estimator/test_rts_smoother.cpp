// The RTS smoother (estimator/smooth): the backward pass against the batch least-squares solution of a linear
// system (closed form), and the smoothed navigation against the simulator's truth inside GNSS outages.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>

#include "estimator/filter/nav_filter.hpp"
#include "estimator/run/run_navigation.hpp"
#include "estimator/smooth/rts_recorder.hpp"
#include "estimator/smooth/transition_product.hpp"
#include "tests/estimator/sim_run.hpp"

namespace ldv::est {
namespace {

// A closed-loop Kalman filter on a linear system, recorded as the navigation filter's epochs are: the estimate
// is corrected by dx = K (H x - z) (predicted minus measured) and the error state reset.
struct LinearRun {
  std::vector<Eigen::VectorXd> x_post;  // forward estimate after each epoch's update
  std::vector<Eigen::MatrixXd> P_post;
};

TEST(RtsBackward, GivenALinearSystem_ThenTheSmoothedStatesAreTheBatchLeastSquaresSolution) {
  // Constant velocity (position, velocity, and a constant bias on the measurement), position measured at
  // most epochs, with a 12-epoch gap.
  const int n = 3, N = 40;
  const double dt = 0.5, q = 0.3, r = 0.2;
  Eigen::Matrix3d F;
  F << 1, dt, 0, 0, 1, 0, 0, 0, 1;
  Eigen::Matrix3d Q = Eigen::Matrix3d::Zero();
  Q.topLeftCorner<2, 2>() << q * dt * dt * dt / 3, q * dt * dt / 2, q * dt * dt / 2, q * dt;
  Q(2, 2) = 1e-4;
  const Eigen::RowVector3d H(1.0, 0.0, 1.0);
  const Eigen::Vector3d x_bar(0.0, 1.0, 0.0);
  const Eigen::Matrix3d P0 = Eigen::Vector3d(4.0, 1.0, 0.25).asDiagonal();
  std::mt19937 rng(5);
  std::normal_distribution<double> g;
  const Eigen::LLT<Eigen::Matrix3d> lq(Q);
  Eigen::Vector3d x_true = x_bar + Eigen::Vector3d(2.0 * g(rng), g(rng), 0.5 * g(rng));
  std::vector<std::optional<double>> z(N);
  for (int k = 0; k < N; ++k) {
    if (k > 0) x_true = F * x_true + lq.matrixL() * Eigen::Vector3d(g(rng), g(rng), g(rng));
    if (k < 15 || k >= 27) z[k] = H.dot(x_true) + std::sqrt(r) * g(rng);
  }

  RtsEpochStore store(n, 0);
  LinearRun fwd;
  Eigen::Vector3d x = x_bar;
  Eigen::Matrix3d P = P0;
  for (int k = 0; k < N; ++k) {
    RtsEpoch e;
    e.t_s = k * dt;
    e.Phi = k == 0 ? Eigen::MatrixXd::Zero(n, n) : Eigen::MatrixXd(F);
    if (k > 0) {
      x = F * x;
      P = F * P * F.transpose() + Q;
    }
    e.P_prior = P;
    e.dx = Eigen::VectorXd::Zero(n);
    if (z[k]) {
      const double S = H * P * H.transpose() + r;
      const Eigen::Vector3d K = P * H.transpose() / S;
      const double y = H.dot(x) - *z[k];
      e.dx = K * y;
      x -= K * y;
      P = (Eigen::Matrix3d::Identity() - K * H) * P;
    }
    e.P_post = P;
    e.x_eff = Eigen::VectorXd(0);
    store.append(e);
    fwd.x_post.push_back(x);
    fwd.P_post.push_back(P);
  }
  const std::vector<SmoothedEpoch> s = rts_backward(store);
  ASSERT_EQ(s.size(), static_cast<size_t>(N));

  // Batch least squares over all states: prior, process and measurement residuals weighted by their inverse
  // covariances; the solution of the normal equations and its covariance.
  const int dim = n * N;
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(dim, dim);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(dim);
  const Eigen::Matrix3d P0i = P0.inverse(), Qi = Q.inverse();
  A.topLeftCorner(n, n) += P0i;
  b.head(n) += P0i * x_bar;
  for (int k = 0; k + 1 < N; ++k) {  // residual x_k+1 - F x_k
    Eigen::MatrixXd J = Eigen::MatrixXd::Zero(n, dim);
    J.block(0, n * k, n, n) = -F;
    J.block(0, n * (k + 1), n, n) = Eigen::Matrix3d::Identity();
    A += J.transpose() * Qi * J;
  }
  for (int k = 0; k < N; ++k)
    if (z[k]) {
      A.block(n * k, n * k, n, n) += H.transpose() * H / r;
      b.segment(n * k, n) += H.transpose() * (*z[k] / r);
    }
  const Eigen::VectorXd x_batch = A.ldlt().solve(b);
  const Eigen::MatrixXd P_batch = A.inverse();

  for (int k = 0; k < N; ++k) {
    const Eigen::Vector3d x_smoothed = fwd.x_post[k] - s[k].dx_post;
    EXPECT_LT((x_smoothed - x_batch.segment(n * k, n)).cwiseAbs().maxCoeff(), 1e-9) << "epoch " << k;
    const Eigen::Vector3d var_batch = P_batch.block(n * k, n * k, n, n).diagonal();
    EXPECT_LT(((s[k].var_smoothed - var_batch).array() / var_batch.array()).abs().maxCoeff(), 1e-9) << "epoch " << k;
  }
  // The last epoch: smoothed equals forward; the middle of the gap: the smoother is far better than forward.
  EXPECT_EQ(s[N - 1].dx_post.norm(), 0.0);
  EXPECT_LT(s[20].var_smoothed(0), 0.5 * fwd.P_post[20](0, 0));
}

TEST(RtsEpochStore, GivenEpochsWrittenAndSomeVoided_ThenTheyReadBackExactly) {
  RtsEpochStore store(4, 1);
  auto epoch = [](double t) {
    RtsEpoch e;
    e.t_s = t;
    e.Phi = Eigen::MatrixXd::Random(4, 4);
    const Eigen::MatrixXd a = Eigen::MatrixXd::Random(4, 4);
    e.P_prior = a * a.transpose();
    e.P_post = 0.5 * e.P_prior;
    e.dx = Eigen::VectorXd::Random(4);
    e.x_eff = Eigen::VectorXd::Random(1);
    return e;
  };
  const RtsEpoch a = epoch(1.0), b = epoch(2.0), c = epoch(2.5);
  store.append(a);
  store.append(epoch(3.0));
  store.truncate(1);  // a rewind to t = 1
  store.append(b);
  store.append(c);
  ASSERT_EQ(store.size(), 3u);
  for (const auto& [k, want] : {std::pair{0, a}, {1, b}, {2, c}}) {
    const RtsEpoch got = store.read(k);
    EXPECT_EQ(got.t_s, want.t_s);
    EXPECT_EQ(got.Phi, want.Phi);
    EXPECT_EQ(got.P_prior, want.P_prior);
    EXPECT_EQ(got.P_post, want.P_post);
    EXPECT_EQ(got.dx, want.dx);
    EXPECT_EQ(got.x_eff, want.x_eff);
  }
}

TEST(TransitionProduct, EqualsTheDenseProduct) {
  // A navigation transition: dense navigation rows, effect rows with a decay on the diagonal and one coupling
  // (a ramp's value driven by its rate).
  const int n = 21;
  Eigen::MatrixXd Phi = Eigen::MatrixXd::Zero(n, n);
  Phi.topRows(kNavDim) = Eigen::MatrixXd::Random(kNavDim, n);
  for (int i = kNavDim; i < n; ++i) Phi(i, i) = 0.99 + 0.001 * i;
  Phi(15, 18) = 0.1;
  const Eigen::MatrixXd M = Eigen::MatrixXd::Random(n, n);
  EXPECT_LT((transition_times(Phi, M) - Phi * M).cwiseAbs().maxCoeff(), 1e-12);
}

// Whatever changes the filter's covariance besides propagation and updates (here a covariance replaced between
// two covariance epochs, and fixes that arrive late and rewind the filter) is seen by the recorder: the
// smoothed variance never exceeds the forward one (smoothing only adds information) and stays finite. (Before
// the filter announced a restart at its covariance epoch, a reset between epochs was dropped and the smoothed
// variances went negative.)
TEST(RtsRecorder, GivenACovarianceResetBetweenEpochsAndLateFixes_ThenTheSmoothedVarianceStaysBelowTheForward) {
  sim::SimRequest req;
  req.grade = "hg1700-typical";
  req.seed = 3;
  req.duration_s = 120.0;
  req.scenario = "figure8";
  req.gnss_rate_hz = 5.0;
  const sim::SimResult sim = sim::simulate(req);
  FilterOptions opt = options_from_kfgins(sim.kfgins);
  opt.history_s = 3.0;
  opt.add.push_back("gnss_position_bias");  // the simulator's RTK errors are time-correlated
  NavFilter filter(opt);
  RtsRecorder recorder(filter);
  filter.set_observer(&recorder);
  NavState s0;
  s0.t_s = sim.imu.front().t_s - sim.imu.front().dt_s;
  s0.pos = *sim.kfgins.init_pos;
  s0.v_n_mps = *sim.kfgins.init_vel_n_mps;
  s0.q_b_n = quat_from_euler(*sim.kfgins.init_rpy_rad);
  filter.initialize(s0, NavStd{});
  std::size_t next_fix = 0;
  bool reset_done = false;
  for (const ImuIncrement& imu : sim.imu) {
    // Fixes handed over 0.3 s late (live: the receiver's latency): each rewinds the filter.
    while (next_fix < sim.gnss.size() && sim.gnss[next_fix].t_s + 0.3 <= imu.t_s) filter.add_gnss(sim.gnss[next_fix++]);
    filter.add_imu(imu);
    recorder.add_row(filter, 0);
    if (!reset_done && imu.t_s - s0.t_s > 60.023) {  // between covariance epochs (every 0.1 s and at fixes)
      filter.set_covariance(Eigen::MatrixXd(filter.covariance().diagonal().asDiagonal()));
      reset_done = true;
    }
  }
  const SmoothedRun run = recorder.smooth();
  ASSERT_GT(run.epochs().size(), 100u);
  int restarts = 0;
  for (const SmoothedEpoch& e : run.epochs()) {
    restarts += e.restart;
    ASSERT_TRUE(e.var_smoothed.allFinite() && e.dx_post.allFinite()) << e.t_s;
    EXPECT_GE(e.var_smoothed.minCoeff(), 0.0) << e.t_s;
    EXPECT_LE((e.var_smoothed - e.var_forward_post).maxCoeff(), 1e-9 * e.var_forward_post.maxCoeff()) << e.t_s;
  }
  EXPECT_GE(restarts, 2) << "the initialisation and the reset at least";
  // Each rewind is a restart to the recorder (nothing passes back across it), so this is nearly the forward
  // solution; it stays consistent: within 4 sigma of the truth at 1 Hz once the filter has settled (10 s).
  const double t0 = sim.truth.front().t_s;
  for (std::size_t i = 2000; i < run.size(); i += 200) {
    const SmoothedRow r = run.row(i);
    const auto& truth = sim.truth[static_cast<std::size_t>(std::llround((r.forward.t_s - t0) * req.imu_rate_hz))];
    const Eigen::Vector3d e = test::nav_error(r.smoothed, truth).head<3>();
    EXPECT_LE(e.cwiseAbs().cwiseQuotient(r.std_smoothed.head<3>()).maxCoeff(), 4.0) << r.forward.t_s;
  }
}

TEST(RtsSmoother, GivenATacticalImuWith60And120sOutagesInTurns_ThenTheSmoothedGapErrorIsATenthOfTheDrift) {
  test::expect_smoothing_works(test::smooth_drive("hg1700-typical", 1, {{120.0, 60.0}, {260.0, 120.0}}, 440.0), 0.1);
}

TEST(RtsSmoother, GivenAMemsImuWith60And120sOutagesInTurns_ThenTheSmoothedGapErrorIsAQuarterOfTheDrift) {
  test::expect_smoothing_works(test::smooth_drive("3dm-gx2-typical", 2, {{120.0, 60.0}, {260.0, 120.0}}, 440.0), 0.25);
}

}  // namespace
}  // namespace ldv::est
