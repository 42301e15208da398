#pragma once
// Shared prior and dynamics of a 3-axis effect whose stochastic model is a BlockOptions
// (constant, random walk or first-order Gauss-Markov per axis).
#include "estimator/effects/effect.hpp"
#include "estimator/options.hpp"

namespace ldv::est {

class Vec3Block : public Effect {
 public:
  explicit Vec3Block(const BlockOptions& o) : o_(o) {}
  int dim() const override { return 3; }
  void prior(Eigen::Ref<Eigen::VectorXd> mean, Eigen::Ref<Eigen::VectorXd> std) const override {
    mean = o_.init;
    std = o_.init_std;
  }
  std::vector<Triplet> dynamics() const override {
    if (o_.process != BlockOptions::Process::kGaussMarkov) return {};
    const double a = -1.0 / o_.corr_time_s;
    return {{0, 0, a}, {1, 1, a}, {2, 2, a}};
  }
  void process_noise(Eigen::Ref<Eigen::VectorXd> q_c) const override {
    switch (o_.process) {
      case BlockOptions::Process::kConstant: q_c.setZero(); break;
      case BlockOptions::Process::kRandomWalk: q_c = o_.rw_density.cwiseAbs2(); break;
      case BlockOptions::Process::kGaussMarkov: q_c = 2.0 * o_.sigma.cwiseAbs2() / o_.corr_time_s; break;
    }
  }
  // The nominal estimate is held between updates, as KF-GINS does: the Gauss-Markov decay acts on the
  // error covariance only, so a turn-on bias that really is constant is not pulled towards zero.

 protected:
  Vec3 v(const Eigen::Ref<const Eigen::VectorXd>& x) const { return x.head<3>(); }
  BlockOptions o_;
};

}  // namespace ldv::est
