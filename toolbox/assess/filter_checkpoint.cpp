#include "toolbox/assess/filter_checkpoint.hpp"

#include <map>

namespace ldv::assess {
namespace {

// The option each 3-state effect takes its prior mean from (estimator/effects/*.cpp).
est::BlockOptions* vec3_prior(est::FilterOptions& o, const std::string& name) {
  const std::map<std::string, est::BlockOptions*> blocks = {
      {"gyro_bias", &o.gyro_bias},
      {"accel_bias", &o.accel_bias},
      {"gyro_scale", &o.gyro_scale},
      {"accel_scale", &o.accel_scale},
      {"gyro_misalignment", &o.gyro_misalignment},
      {"accel_misalignment", &o.accel_misalignment},
      {"g_sensitivity", &o.g_sensitivity},
      {"lever_arm", &o.lever_arm},
      {"gravity_anomaly", &o.gravity_anomaly},
  };
  const auto it = blocks.find(name);
  return it == blocks.end() ? nullptr : it->second;
}

}  // namespace

FilterCheckpoint capture_checkpoint(const est::NavFilter& f) {
  FilterCheckpoint c;
  c.options = f.options();
  c.state = f.state();
  c.covariance = f.covariance();
  const Eigen::VectorXd& x = f.effect_state();
  for (const est::StateBlock& b : f.layout().blocks()) {
    const std::string name = b.effect->name();
    const auto seg = x.segment(b.offset - est::kNavDim, b.dim);
    if (est::BlockOptions* prior = vec3_prior(c.options, name); prior && b.dim == 3) {
      prior->init = seg;
    } else if (name == "time_offset") {
      c.options.time_offset_init_s = seg(0);
    } else if (name == "gyro_moving_bias" || name == "accel_moving_bias") {
      // The moving bias starts from the gyro/accel bias prior in its constant part: carry the sum of
      // constant + Gauss-Markov + random walk + ramp value there; the ramp rate is not carried.
      const Vec3 total = seg.segment<3>(0) + seg.segment<3>(3) + seg.segment<3>(6) + seg.segment<3>(9);
      (name == "gyro_moving_bias" ? c.options.gyro_bias : c.options.accel_bias).init = total;
      if (seg.segment<3>(12).squaredNorm() > 0.0) c.not_carried.push_back(name + " ramp rate");
      // The covariance restored below is for the split states; the nominal split differs (sum in the
      // constant), which only matters for how later updates share a correction: none during an outage.
    } else {
      c.not_carried.push_back(name);
    }
  }
  return c;
}

std::unique_ptr<est::NavFilter> restore_filter(const FilterCheckpoint& c) {
  auto f = std::make_unique<est::NavFilter>(c.options);
  f->initialize(c.state, est::NavStd{});
  f->set_covariance(c.covariance);
  return f;
}

}  // namespace ldv::assess
