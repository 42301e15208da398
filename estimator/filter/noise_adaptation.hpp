#pragma once
// The noise the GNSS position innovations call for, split between its two sources: a factor alpha on the IMU
// white-noise PSDs (above the installed floor) and a factor beta on the GNSS position variance the receiver
// states. One NIS-driven factor on the IMU alone sent every excess into the IMU noise: optimistic RTK
// sigmas took a drive whose configured IMU noise was the truth to 12x, a real car to its 1e4 cap, and an
// unmodelled lever arm or lag hid in it.
//
// The two are told apart by the innovations' whiteness (Mehra: at the right noise an optimal filter's
// innovations are white). Per fix, with S = A + R (A = H P- H^T, the prediction's part, carrying alpha;
// R = beta R_stated) and the score and Fisher information of a Gaussian in the log of a factor on a part D of S,
//   g(D) = (u'Du - tr(WD)) / 2,  F(D) = tr(WDWD) / 2,  W = S^-1, u = W y,
// beta follows g(R) of the difference of consecutive innovations (a white excess keeps its variance there: GNSS
// noise above the stated), alpha the excess the differences do not show, g(A) of the innovation minus g(A) of the
// difference (a positive correlation: a prediction too confident for the IMU's noise; a transient after a wrong
// initial state). Each is a recursive MAP step over a forgetting window (kWindow_s) against a log-normal prior
// centred on the configured noise (sigma 1 on each ln; on alpha 0.5 once a standstill measured the IMU noise).
// A structured residual (a missing lever arm, lag or scale) is correlated and goes to alpha only as far as its
// prior allows: what is left shows in the whiteness below, for ldv diagnose to name.
//
// beta is kept per solution quality (fixed, float, other: single, DGPS, SBAS): a receiver's stated std is off by
// its own factor in each, and a drive moves between them. Fixes of one class pair only with fixes of that class.
// In NavFilter with FilterOptions::split_noise_adaptation (the GNSS position update's R times beta of its class;
// alpha on top of the installed floor); tests/estimator/test_noise_adaptation.cpp checks it against closed forms.
//
// Also kept: the lag-1 correlation of the whitened innovations (L^-1 y, S = L L^T) between consecutive fixes. A
// consistent model gives white innovations; a correlation well beyond 3 / sqrt(pairs) says the model misses
// something or the GNSS errors are correlated in time.
#include <Eigen/Core>

namespace ldv::est {

class NoiseAdaptation {
 public:
  static constexpr int kGnssClasses = 3;  // 0 fixed (and PPP), 1 float, 2 other (single, DGPS, SBAS)
  static const char* gnss_class_name(int gnss_class);
  // One GNSS position fix at t_s of class gnss_class: A and R as above (the R the update used), y the innovation
  // capped at the gate.
  void add_fix(double t_s, const Eigen::MatrixXd& A, const Eigen::MatrixXd& R, const Eigen::VectorXd& y,
               int gnss_class = 0);
  // The IMU noise was measured as installed (a standstill in the data): alpha's prior narrows to what that
  // measurement leaves open (vibration on the move above the standstill's), so an excess the prediction cannot
  // explain at the measured noise is not taken for noise.
  void set_imu_noise_measured();
  double imu_scale() const;                     // alpha, >= 1
  double gnss_scale(int gnss_class = 0) const;  // beta of a class, on the variance, >= 1
  // The 1-sigma of each factor: the curvature of the windowed log-likelihood and the prior at the estimate (the
  // factor times the sigma of its log; at a bound the estimate is clamped and this says how sure the data are).
  double imu_scale_sigma() const;
  double gnss_scale_sigma(int gnss_class = 0) const;
  long gnss_fixes(int gnss_class) const { return class_fixes_[gnss_class]; }
  // The prediction's mean share of the innovation covariance, tr(A S^-1) / rows, over the fixes seen.
  double prediction_share() const { return fixes_ > 0 ? share_sum_ / static_cast<double>(fixes_) : 0.0; }
  long fixes() const { return fixes_; }
  // Lag-1 correlation of the whitened innovations over consecutive fixes (NaN before two), and the products
  // it rests on (rows per pair): its sigma when white is about 1 / sqrt(products).
  double lag1_correlation() const;
  long lag1_products() const { return products_; }

 private:
  // ln alpha, then ln beta of each class
  using Factors = Eigen::Matrix<double, 1 + kGnssClasses, 1>;
  Factors theta_ = Factors::Zero();
  Factors information_ = Factors::Zero();
  struct Fix {
    Eigen::VectorXd y;
    Eigen::MatrixXd A, R;
    int gnss_class = 0;
  } last_;
  Factors prior_precision_ = Factors::Ones();
  long class_fixes_[kGnssClasses] = {0, 0, 0};
  double last_t_s_ = 0.0;
  long fixes_ = 0;
  double share_sum_ = 0.0;
  Eigen::VectorXd last_white_;
  double sum_xy_ = 0.0, sum_xx_ = 0.0, sum_yy_ = 0.0;
  long products_ = 0;
};

}  // namespace ldv::est
