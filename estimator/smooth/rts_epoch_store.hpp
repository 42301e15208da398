#pragma once
// The forward pass's covariance epochs, as the Rauch-Tung-Striebel backward pass reads them. Written in time
// order, read back in any order. The records live in an unnamed temporary file (in $TMPDIR, else /tmp), not in
// RAM: 1 h of a 51-state model with 5 Hz RTK is 18,000 epochs of 43 KB (770 MB; an aid every 0.1 s doubles it);
// only their times stay in memory.
#include <Eigen/Core>
#include <cstdio>
#include <vector>

namespace ldv::est {

// One covariance epoch of the forward error-state filter (closed loop: the nominal is corrected and the
// error state reset after each update).
struct RtsEpoch {
  double t_s = 0.0;
  Eigen::MatrixXd Phi;      // transition from the previous epoch to this one (0: no relation, a restart)
  Eigen::MatrixXd P_prior;  // covariance before this epoch's updates
  Eigen::MatrixXd P_post;   // after them
  Eigen::VectorXd dx;       // this epoch's corrections summed (the filter applied x_hat -= dx)
  Eigen::VectorXd x_eff;    // the effect states' nominal values after them
};

class RtsEpochStore {
 public:
  // n: error states; m: effect states (the last m of them).
  RtsEpochStore(int n, int m);
  ~RtsEpochStore();
  RtsEpochStore(const RtsEpochStore&) = delete;
  RtsEpochStore& operator=(const RtsEpochStore&) = delete;

  void append(const RtsEpoch& e);
  RtsEpoch read(std::size_t k) const;
  void truncate(std::size_t count);
  std::size_t size() const { return t_s_.size(); }
  double t_s(std::size_t k) const { return t_s_[k]; }
  const std::vector<double>& times_s() const { return t_s_; }
  int n() const { return n_; }
  int m() const { return m_; }
  std::size_t bytes_on_disk() const { return size() * record_doubles_ * sizeof(double); }  // of the records kept

 private:
  void write_at(std::size_t k, const RtsEpoch& e);
  void seek_to(std::size_t k) const;
  int n_, m_;
  std::size_t record_doubles_;
  std::FILE* file_ = nullptr;
  std::vector<double> t_s_;
  mutable std::vector<double> buf_;
};

}  // namespace ldv::est
