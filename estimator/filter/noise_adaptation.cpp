#include "estimator/filter/noise_adaptation.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

namespace ldv::est {
namespace {
// The data's memory: vibration changes with speed and road, over minutes.
constexpr double kWindow_s = 120.0;
// The fastest the IMU noise as installed changes: a factor e in this time.
constexpr double kImuNoiseTime_s = 10.0;
// The prior on each ln factor: the configured noise within a factor e (1 sigma); the IMU noise measured at a
// standstill within a factor 1.65 (road vibration on the move above the standstill's engine idle).
constexpr double kLnSigmaMeasuredImu = 0.5;
// alpha: the configured (installed) noise is the floor; 1e4 on the PSD is 100x the noise density.
const double kMaxLnImu = std::log(1e4);
// beta: the stated GNSS std is its floor, up to 100x. Innovations smaller than the stated noise say the errors
// are correlated in time (the state follows them: the simulator's RTK, half white and half a 60 s Gauss-Markov
// process, gave beta 0.54), not that the receiver is better than it says.
const double kMinLnGnss = 0.0, kMaxLnGnss = std::log(1e4);
// Fixes further apart than this are not "consecutive" for the whiteness check (an outage between).
constexpr double kMaxPairGap_s = 2.0;

// 0.5 (u'Du - tr(WD)) and 0.5 tr(WDWD) with u = W y: the score and Fisher information of a Gaussian y ~ N(0, S)
// in the log of a factor on D, a part of S.
struct Score {
  double g = 0.0, information = 0.0;
};
Score score(const Eigen::MatrixXd& W, const Eigen::VectorXd& y, const Eigen::MatrixXd& D) {
  const Eigen::VectorXd u = W * y;
  const Eigen::MatrixXd WD = W * D;
  return {0.5 * (u.dot(D * u) - WD.trace()), 0.5 * (WD * WD).trace()};
}
}  // namespace

const char* NoiseAdaptation::gnss_class_name(int gnss_class) {
  static const char* const names[kGnssClasses] = {"fixed", "float", "single/DGPS"};
  return gnss_class >= 0 && gnss_class < kGnssClasses ? names[gnss_class] : "?";
}

void NoiseAdaptation::add_fix(double t_s, const Eigen::MatrixXd& A, const Eigen::MatrixXd& R, const Eigen::VectorXd& y,
                              int gnss_class) {
  gnss_class = std::clamp(gnss_class, 0, kGnssClasses - 1);
  const Eigen::MatrixXd S = A + R;
  const Eigen::LLT<Eigen::MatrixXd> llt(S);
  if (llt.info() != Eigen::Success || !y.allFinite() || !A.allFinite() || !R.allFinite()) return;
  const Eigen::MatrixXd W = llt.solve(Eigen::MatrixXd::Identity(S.rows(), S.cols()));
  const bool paired =
      fixes_ > 0 && last_.y.size() == y.size() && t_s - last_t_s_ <= kMaxPairGap_s && last_.gnss_class == gnss_class;
  if (paired) {
    // Differences of consecutive innovations: a white sequence keeps its variance in them (E[dd'] = S + S_prev),
    // a correlated one (a filter that lags, a transient, a missing effect) loses it.
    const Eigen::VectorXd d = y - last_.y;
    const Eigen::MatrixXd A_d = A + last_.A, R_d = R + last_.R;
    const Eigen::LLT<Eigen::MatrixXd> llt_d(A_d + R_d);
    if (llt_d.info() == Eigen::Success) {
      const Eigen::MatrixXd W_d = llt_d.solve(Eigen::MatrixXd::Identity(S.rows(), S.cols()));
      // beta: the level of the white part; alpha: the excess the differences do not show (the innovations'
      // positive correlation, which a prediction too confident makes and GNSS white noise cannot), and all of a
      // deficit (innovations below their expectation: the noise is too large whatever its colour). Without
      // the latter, white innovations leave alpha without a restoring force: a random walk held at its floor,
      // which drifts up.
      const Score b = score(W_d, d, R_d), a_all = score(W, y, A), a_white = score(W_d, d, A_d);
      const int ib = 1 + gnss_class;  // this class's beta; the other classes' keep their value
      const double dt_s = std::max(t_s - last_t_s_, 0.0);
      const double keep = std::exp(-dt_s / kWindow_s);
      information_ *= keep;
      information_(0) += a_all.information;
      information_(ib) += b.information;
      const double g[2] = {a_all.g - std::max(a_white.g, 0.0), b.g};
      const int index[2] = {0, ib};
      for (int k = 0; k < 2; ++k) {
        const int i = index[k];
        double step = (g[k] - (1.0 - keep) * prior_precision_(i) * theta_(i)) / (information_(i) + prior_precision_(i));
        // alpha moves by a factor e in kImuNoiseTime_s at most: the noise as installed changes with road and speed
        // over tens of seconds; what changes faster (a misstated initial state leaving the fixes in seconds) is a
        // state error, the re-synchronisation's and the heading check's to take up.
        if (i == 0) step = std::clamp(step, -dt_s / kImuNoiseTime_s, dt_s / kImuNoiseTime_s);
        theta_(i) += step;
      }
      theta_(0) = std::clamp(theta_(0), 0.0, kMaxLnImu);
      theta_(ib) = std::clamp(theta_(ib), kMinLnGnss, kMaxLnGnss);
    }
  }
  share_sum_ += (W * A).trace() / static_cast<double>(S.rows());
  const Eigen::VectorXd white = llt.matrixL().solve(y);
  if (paired && last_white_.size() == white.size()) {
    sum_xy_ += white.dot(last_white_);
    sum_xx_ += white.squaredNorm();
    sum_yy_ += last_white_.squaredNorm();
    products_ += white.size();
  }
  last_white_ = white;
  last_ = {y, A, R, gnss_class};
  last_t_s_ = t_s;
  ++fixes_;
  ++class_fixes_[gnss_class];
}

void NoiseAdaptation::set_imu_noise_measured() {
  prior_precision_(0) = 1.0 / (kLnSigmaMeasuredImu * kLnSigmaMeasuredImu);
}

double NoiseAdaptation::imu_scale() const { return std::exp(theta_(0)); }
double NoiseAdaptation::gnss_scale(int gnss_class) const {
  return std::exp(theta_(1 + std::clamp(gnss_class, 0, kGnssClasses - 1)));
}

double NoiseAdaptation::imu_scale_sigma() const {
  return imu_scale() / std::sqrt(information_(0) + prior_precision_(0));
}

double NoiseAdaptation::gnss_scale_sigma(int gnss_class) const {
  const int i = 1 + std::clamp(gnss_class, 0, kGnssClasses - 1);
  return gnss_scale(gnss_class) / std::sqrt(information_(i) + prior_precision_(i));
}

double NoiseAdaptation::lag1_correlation() const {
  return products_ > 0 && sum_xx_ > 0.0 && sum_yy_ > 0.0 ? sum_xy_ / std::sqrt(sum_xx_ * sum_yy_) : NAN;
}

}  // namespace ldv::est
