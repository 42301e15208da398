#include "estimator/smooth/rts_recorder.hpp"

#include <algorithm>
#include <cmath>

#include "common/geo/earth_model.hpp"
#include "estimator/filter/nav_filter.hpp"
#include "estimator/smooth/transition_product.hpp"

namespace ldv::est {
namespace {
constexpr double kSameEpoch_s = 1e-6;  // accumulated sample intervals differ from the tags by rounding
}  // namespace

RtsRecorder::RtsRecorder(const NavFilter& filter)
    : filter_(filter), store_(filter.layout().size(), filter.layout().effect_dim()) {}

void RtsRecorder::close_current() {
  if (current_) store_.append(*current_);
  current_.reset();
  current_updated_ = false;
}

void RtsRecorder::void_after(double t_s) {
  if (current_ && current_->t_s > t_s + kSameEpoch_s) current_.reset();
  close_current();
  const std::vector<double>& t = store_.times_s();
  store_.truncate(std::upper_bound(t.begin(), t.end(), t_s + kSameEpoch_s) - t.begin());
}

void RtsRecorder::on_propagation(double t_s, double dt_s, const Eigen::MatrixXd& Phi, const Eigen::MatrixXd&) {
  const bool continues = current_ && std::abs(current_->t_s - (t_s - dt_s)) <= kSameEpoch_s;
  const double last_kept_t_s = store_.size() > 0 ? store_.t_s(store_.size() - 1) : -1e300;
  if (continues && !current_updated_ && t_s - last_kept_t_s <= kMaxEpochSpan_s + kSameEpoch_s) {
    // Nothing happened at the current epoch: this propagation extends it.
    current_->Phi = transition_times(Phi, current_->Phi);
    current_->t_s = t_s;
    current_->P_prior = current_->P_post = filter_.covariance();
    current_->x_eff = filter_.effect_state();
    return;
  }
  void_after(t_s - dt_s);  // normally nothing: the last epoch is where this propagation starts
  RtsEpoch e;
  e.t_s = t_s;
  // No epoch to start from (observed from mid-run): this one starts afresh.
  e.Phi = store_.size() > 0 ? Phi : Eigen::MatrixXd::Zero(Phi.rows(), Phi.cols());
  e.P_prior = e.P_post = filter_.covariance();
  e.dx = Eigen::VectorXd::Zero(Phi.rows());
  e.x_eff = filter_.effect_state();
  current_ = std::move(e);
}

void RtsRecorder::on_update(const InnovationRecord& r, const Eigen::MatrixXd&, const Eigen::MatrixXd& K) {
  if (!current_ || K.cols() != r.innovation.size() || !r.accepted) return;
  current_->dx += K * r.innovation;
  current_updated_ = true;
  current_->P_post = filter_.covariance();
  current_->x_eff = filter_.effect_state();
}

void RtsRecorder::on_restart(double t_s, const Eigen::MatrixXd& P) {
  void_after(t_s);
  RtsEpoch e;
  e.t_s = t_s;
  e.Phi = Eigen::MatrixXd::Zero(P.rows(), P.cols());
  e.P_prior = e.P_post = P;
  e.dx = Eigen::VectorXd::Zero(P.rows());
  e.x_eff = filter_.effect_state();
  current_ = std::move(e);
  current_updated_ = true;  // a restart is kept as it is
}

void RtsRecorder::add_row(const NavFilter& f, int week) {
  const double t = f.state().t_s;
  // A redone alignment navigates again from an earlier epoch: its rows replace the abandoned ones.
  while (!rows_.empty() && rows_.back().second.t_s >= t - 1e-9) rows_.pop_back();
  rows_.emplace_back(week, f.state());
}

SmoothedRun RtsRecorder::smooth(const std::function<void(double)>& progress) {
  close_current();
  return SmoothedRun(rts_backward(store_, progress), std::move(rows_), store_.m());
}

SmoothedRun::SmoothedRun(std::vector<SmoothedEpoch> epochs, std::vector<std::pair<int, NavState>> rows, int effect_dim)
    : epochs_(std::move(epochs)), rows_(std::move(rows)), effect_dim_(effect_dim) {
  epoch_t_s_.reserve(epochs_.size());
  for (const SmoothedEpoch& e : epochs_) epoch_t_s_.push_back(e.t_s);
}

SmoothedRow SmoothedRun::row(std::size_t i) const {
  SmoothedRow out;
  out.week = rows_.at(i).first;
  out.forward = rows_[i].second;
  out.smoothed = out.forward;
  if (epochs_.empty()) {  // nothing recorded (a filter that never started): the forward row, no std
    out.x_eff_smoothed = out.std_eff_smoothed = Eigen::VectorXd::Zero(effect_dim_);
    return out;
  }
  const double t = out.forward.t_s;
  // The epoch the row's nominal was propagated from (the last at or before it, after its updates), and the
  // next one (before its updates).
  auto after = std::upper_bound(epoch_t_s_.begin(), epoch_t_s_.end(), t + kSameEpoch_s);
  const std::size_t k = after == epoch_t_s_.begin() ? 0 : static_cast<std::size_t>(after - epoch_t_s_.begin()) - 1;
  const SmoothedEpoch& a = epochs_[k];
  Eigen::VectorXd dx = a.dx_post, var_s = a.var_smoothed, var_f = a.var_forward_post;
  if (k + 1 < epochs_.size() && t > a.t_s && !epochs_[k + 1].restart) {
    const SmoothedEpoch& b = epochs_[k + 1];
    const double w = std::clamp((t - a.t_s) / (b.t_s - a.t_s), 0.0, 1.0);
    dx = (1.0 - w) * a.dx_post + w * b.dx_prior;
    var_s = (1.0 - w) * a.var_smoothed + w * b.var_smoothed;
    var_f = (1.0 - w) * a.var_forward_post + w * b.var_forward_prior;
  }
  NavState& s = out.smoothed;
  s.pos = earth::offset_ned(s.pos, -dx.segment<3>(kPos));
  s.v_n_mps -= dx.segment<3>(kVel);
  s.q_b_n = (quat_from_rotvec(dx.segment<3>(kAtt)) * s.q_b_n).normalized();
  out.separation = dx.head<kNavDim>();
  out.std_forward = var_f.head<kNavDim>().cwiseMax(0.0).cwiseSqrt();
  out.std_smoothed = var_s.head<kNavDim>().cwiseMax(0.0).cwiseSqrt();
  out.std_separation = (var_f - var_s).head<kNavDim>().cwiseMax(0.0).cwiseSqrt();
  const int m = static_cast<int>(dx.size()) - kNavDim;
  out.x_eff_smoothed = a.x_eff - dx.tail(m);
  out.std_eff_smoothed = var_s.tail(m).cwiseMax(0.0).cwiseSqrt();
  return out;
}

}  // namespace ldv::est
