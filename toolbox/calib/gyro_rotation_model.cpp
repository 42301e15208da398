#include "toolbox/calib/gyro_rotation_model.hpp"

#include <cmath>

namespace ldv::calib {

Mat3 integrate_attitude(const ImuLog& log, size_t begin, size_t end, const TriadCalibration& gyro,
                        const Vec3& bias_begin, const Vec3& bias_end) {
  const Mat3 Minv = gyro.sensor_matrix().inverse();
  const double t0 = log.t_s[begin], span = std::max(log.t_s[end] - t0, 1e-12);
  auto rate = [&](size_t i) {
    const double a = (log.t_s[i] - t0) / span;
    return Vec3(Minv * (log.w_rad_s[i] - ((1.0 - a) * bias_begin + a * bias_end)));
  };
  Quat q = Quat::Identity();
  Vec3 w_prev = rate(begin);
  for (size_t i = begin + 1; i <= end; ++i) {
    const Vec3 w = rate(i);
    q = q * quat_from_rotvec(0.5 * (w_prev + w) * (log.t_s[i] - log.t_s[i - 1]));  // trapezoid
    w_prev = w;
  }
  return q.normalized().toRotationMatrix();
}

namespace {

// Orthonormal 2x3 basis of the plane perpendicular to u, built from the body axis `k` (smooth in u while u
// stays away from that axis).
Eigen::Matrix<double, 2, 3> tangent_basis(const Vec3& u, int k) {
  const Vec3 p1 = u.cross(Vec3::Unit(k)).normalized();
  const Vec3 p2 = u.cross(p1);
  Eigen::Matrix<double, 2, 3> P;
  P.row(0) = p1.transpose();
  P.row(1) = p2.transpose();
  return P;
}

TriadCalibration gyro_from_params(const VectorXd& x) {
  TriadCalibration g;
  g.scale = x.segment<3>(0);
  g.misalignment_rad = x.segment<3>(3);
  g.frame_rotation_rad = x.segment<3>(6);
  return g;
}

}  // namespace

std::vector<bool> find_clipped_samples(const ImuLog& log, double full_scale_rad_s) {
  std::vector<bool> clipped(log.w_rad_s.size(), false);
  if (log.w_rad_s.empty()) return clipped;
  for (int axis = 0; axis < 3; ++axis) {
    double lo = INFINITY, hi = -INFINITY;
    for (const Vec3& w : log.w_rad_s) lo = std::min(lo, w[axis]), hi = std::max(hi, w[axis]);
    size_t n_lo = 0, n_hi = 0;
    for (const Vec3& w : log.w_rad_s) n_lo += w[axis] == lo, n_hi += w[axis] == hi;
    // A two's-complement range clips at -2^15 and 2^15 - 1: one clipped side marks its mirror too.
    const bool clip_lo = n_lo >= 3 || (n_hi >= 3 && std::abs(lo) >= 0.999 * std::abs(hi));
    const bool clip_hi = n_hi >= 3 || (n_lo >= 3 && std::abs(hi) >= 0.999 * std::abs(lo));
    for (size_t i = 0; i < clipped.size(); ++i) {
      const double w = log.w_rad_s[i][axis];
      if ((clip_lo && w == lo) || (clip_hi && w == hi) || (full_scale_rad_s > 0 && std::abs(w) >= full_scale_rad_s))
        clipped[i] = true;
    }
  }
  return clipped;
}

GyroRotationModel::GyroRotationModel(const ImuLog& log, const std::vector<Pose>& poses, const TriadCalibration& accel,
                                     const std::vector<bool>& clipped)
    : log_(log), poses_(poses), accel_(accel) {
  for (size_t k = 0; k + 1 < poses.size(); ++k) {
    bool any = false;
    for (size_t i = poses[k].end - 1; i <= poses[k + 1].begin && !any; ++i) any = clipped[i];
    (any ? clipped_transitions_ : transitions_).push_back(k);
  }
  // Each transition's basis axis chosen once, from its end pose's measured gravity (the axis of its smallest
  // component): chosen anew at every evaluation it switched between tied axes at an exact cube pose (two
  // components 0), and the adjustment straddling the switch did not converge (2-3 of 3 seeds).
  for (size_t k : transitions_) {
    int axis = 0;
    poses[k + 1].f_mean_mps2.cwiseAbs().minCoeff(&axis);
    basis_axis_.push_back(axis);
  }
}

std::vector<std::string> GyroRotationModel::param_names() const {
  return {"gyro_scale_x",        "gyro_scale_y",        "gyro_scale_z",
          "gyro_misalignment_x", "gyro_misalignment_y", "gyro_misalignment_z",
          "gyro_rotation_x",     "gyro_rotation_y",     "gyro_rotation_z"};
}

VectorXd GyroRotationModel::param_ranges() const { return VectorXd::Constant(9, 0.2); }

VectorXd GyroRotationModel::misclosure(int k, const VectorXd& l, const VectorXd& x) const {
  const Pose& a = poses_[transitions_[k]];
  const Pose& b = poses_[transitions_[k] + 1];
  const Vec3 u0 = accel_.correct(l.head<3>()).normalized();
  const Vec3 u1 = accel_.correct(l.tail<3>()).normalized();
  const Mat3 C = integrate_attitude(log_, a.end - 1, b.begin, gyro_from_params(x), a.w_mean_rad_s, b.w_mean_rad_s);
  // Gravity is fixed in the (quasi-inertial) start frame: its direction in the end frame is C' u0.
  return tangent_basis(u1, basis_axis_[k]) * (C.transpose() * u0 - u1);
}

void GyroRotationModel::evaluate(int k, const VectorXd& l, const VectorXd& x, VectorXd& f, MatrixXd& A,
                                 MatrixXd& B) const {
  const VectorXd dx = VectorXd::Constant(9, 1e-6);
  const VectorXd dl = VectorXd::Constant(6, 1e-5);
  numeric_jacobians([this, k](const VectorXd& ll, const VectorXd& xx) { return misclosure(k, ll, xx); }, l, x, dl, dx,
                    f, A, B);
}

std::vector<ConditionBlock> GyroRotationModel::blocks() const {
  std::vector<ConditionBlock> out;
  for (size_t k : transitions_) {
    const Pose& a = poses_[k];
    const Pose& b = poses_[k + 1];
    ConditionBlock blk;
    blk.l.resize(6);
    blk.l << a.f_mean_mps2, b.f_mean_mps2;
    blk.Sigma_l = MatrixXd::Zero(6, 6);
    blk.Sigma_l.topLeftCorner<3, 3>() = a.f_mean_cov;
    blk.Sigma_l.bottomRightCorner<3, 3>() = b.f_mean_cov;
    // Angle random walk over the motion: per-sample rate variance * dt * duration, per tangent axis.
    const double rate_var = 0.5 * (a.w_sample_cov.trace() + b.w_sample_cov.trace()) / 3.0;
    const double duration_s = log_.t_s[b.begin] - log_.t_s[a.end - 1];
    // Plus the error of the interpolated bias: T (e_a + e_b) / 2 from the two pose means' uncertainty.
    const double bias_var = (a.w_mean_cov.trace() + b.w_mean_cov.trace()) / 3.0 * duration_s * duration_s / 4.0;
    blk.Q_extra = MatrixXd::Identity(2, 2) * (rate_var * log_.dt_s * duration_s + bias_var);
    out.push_back(blk);
  }
  return out;
}

TriadCalibration GyroRotationModel::to_triad(const VectorXd& x, const VectorXd& sigma) const {
  TriadCalibration g = gyro_from_params(x);
  g.scale_sigma = sigma.segment<3>(0);
  g.misalignment_sigma_rad = sigma.segment<3>(3);
  g.frame_rotation_sigma_rad = sigma.segment<3>(6);
  // The bias is the log's average static reading (a MEMS turn-on bias: re-measure it at start-up); its
  // sigma is the pose-to-pose scatter, i.e. how much it drifted during the log.
  Vec3 mean = Vec3::Zero();
  for (const Pose& p : poses_) mean += p.w_mean_rad_s;
  mean /= static_cast<double>(poses_.size());
  Vec3 var = Vec3::Zero();
  for (const Pose& p : poses_) var += (p.w_mean_rad_s - mean).cwiseAbs2();
  g.bias = mean;
  g.bias_sigma = (var / std::max<double>(1.0, poses_.size() - 1.0)).cwiseSqrt();
  return g;
}

double GyroRotationModel::angle_residual_rad(int k, const VectorXd& x) const {
  const Pose& a = poses_[transitions_[k]];
  const Pose& b = poses_[transitions_[k] + 1];
  const Vec3 u0 = accel_.correct(a.f_mean_mps2).normalized();
  const Vec3 u1 = accel_.correct(b.f_mean_mps2).normalized();
  const Mat3 C = integrate_attitude(log_, a.end - 1, b.begin, gyro_from_params(x), a.w_mean_rad_s, b.w_mean_rad_s);
  return std::acos(std::clamp((C.transpose() * u0).dot(u1), -1.0, 1.0));
}

}  // namespace ldv::calib
