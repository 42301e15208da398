#pragma once
// RtsRecorder: watches a forward NavFilter run (as its observer) and keeps what the RTS smoother needs: the
// covariance epochs (rts_epoch_store.hpp, on disk) and the forward solution at every IMU epoch (add_row, in
// RAM: 96 bytes a row, 66 MB for 1 h at 200 Hz). smooth() then runs the backward pass (rts_backward.hpp)
// and gives each row its smoothed state.
//
// Epochs without an update are merged into the next (Phi multiplied, the later covariance kept: the backward pass
// gives the same result at the epochs kept), up to kMaxEpochSpan_s apart; between two epochs the nominal is
// propagated from the first one, so a row's smoothed error is interpolated linearly in time between the first
// epoch's post-update value and the second's pre-update one (the error grows smoothly: over 0.5 s the
// interpolation is far inside the smoothed sigma).
// A late reading that rewinds the filter (live use) is a restart to the recorder (nothing passes back across it,
// and rows already recorded after it are not replaced): this is for forward passes over files, where readings
// are handed to the filter ahead of the IMU.
#include <optional>
#include <vector>

#include "estimator/filter/records.hpp"
#include "estimator/ins/nav_state.hpp"
#include "estimator/smooth/rts_backward.hpp"

namespace ldv::est {

class NavFilter;  // nav_filter.hpp (watched, never held)

using Vec9 = Eigen::Matrix<double, 9, 1>;

// One row of the smoothed solution.
struct SmoothedRow {
  int week = 0;
  NavState forward, smoothed;
  Vec9 separation = Vec9::Zero();                    // forward minus smoothed: NED [m], NED [m/s], attitude error [rad]
  Vec9 std_forward = Vec9::Zero();                   // 1-sigma of the forward navigation error
  Vec9 std_smoothed = Vec9::Zero();                  // and of the smoothed one
  Vec9 std_separation = Vec9::Zero();                // 1-sigma of the separation: sqrt(P forward - P smoothed)
  Eigen::VectorXd x_eff_smoothed, std_eff_smoothed;  // the effect states (layout offsets minus 9), SI
};

class SmoothedRun {
 public:
  SmoothedRun(std::vector<SmoothedEpoch> epochs, std::vector<std::pair<int, NavState>> rows, int effect_dim);
  std::size_t size() const { return rows_.size(); }
  double t_s(std::size_t i) const { return rows_[i].second.t_s; }
  SmoothedRow row(std::size_t i) const;
  const std::vector<SmoothedEpoch>& epochs() const { return epochs_; }

 private:
  std::vector<SmoothedEpoch> epochs_;
  std::vector<double> epoch_t_s_;
  std::vector<std::pair<int, NavState>> rows_;
  int effect_dim_;
};

class RtsRecorder final : public FilterObserver {
 public:
  // `filter` is the one observed (set_observer(this) on it before it is initialised).
  explicit RtsRecorder(const NavFilter& filter);

  bool wants_matrices() const override { return true; }
  void on_propagation(double t_s, double dt_s, const Eigen::MatrixXd& Phi, const Eigen::MatrixXd& Qd) override;
  void on_update(const InnovationRecord& r, const Eigen::MatrixXd& H, const Eigen::MatrixXd& K) override;
  void on_restart(double t_s, const Eigen::MatrixXd& P) override;
  // The forward solution at an IMU epoch (the filter after its sample; RunCallbacks::on_epoch).
  void add_row(const NavFilter& f, int week);

  static constexpr double kMaxEpochSpan_s = 0.5;
  std::size_t epochs() const { return store_.size() + (current_ ? 1 : 0); }
  std::size_t rows() const { return rows_.size(); }
  std::size_t bytes_on_disk() const { return store_.bytes_on_disk(); }
  // Ends the forward pass and runs the backward one (progress: done fraction).
  SmoothedRun smooth(const std::function<void(double)>& progress = {});

 private:
  void close_current();
  void void_after(double t_s);  // a rewind or restart: what was recorded after t_s no longer holds

  const NavFilter& filter_;
  RtsEpochStore store_;
  std::optional<RtsEpoch> current_;  // the last epoch, still taking its updates
  bool current_updated_ = false;     // it has taken one (or is a restart): it is kept, not merged
  std::vector<std::pair<int, NavState>> rows_;
};

}  // namespace ldv::est
