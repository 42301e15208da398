#pragma once
// Given a simulated drive with (at most) one hidden effect, when `ldv diagnose` runs on it: the
// helpers that build the drive and the inputs in memory (no files).
#include <string>
#include <vector>

#include "estimator/run/run_navigation.hpp"
#include "sim/simulator.hpp"
#include "toolbox/diagnose/diagnosis.hpp"

namespace ldv::diag::testing {

struct SimCase {
  std::string grade = "hg1700-typical";
  std::string effect;  // "" = none; "NAME" or "NAME=v1,v2,v3" (sim/README.md units)
  uint64_t seed = 1;
  double duration_s = 900.0;
  std::string scenario = "drive";
  double gnss_rate_hz = 1.0;
  std::vector<sim::Outage> outages;
};

inline sim::SimResult simulate(const SimCase& c) {
  sim::SimRequest req;
  req.grade = c.grade;
  req.seed = c.seed;
  req.duration_s = c.duration_s;
  req.scenario = c.scenario;
  req.gnss_rate_hz = c.gnss_rate_hz;
  if (!c.effect.empty()) req.effects.push_back(c.effect);
  req.outages = c.outages;
  return sim::simulate(req);
}

inline DiagnoseInputs inputs(const sim::SimResult& r) {
  DiagnoseInputs in;
  in.imu = r.imu;
  in.gnss = r.gnss;
  in.cfg = r.kfgins;
  for (const sim::TruthSample& t : r.truth) {
    NavRecord n;
    n.sow_s = t.t_s;
    n.pos = t.pos;
    n.vel_n_mps = t.vel_n_mps;
    n.rpy_rad = t.rpy_rad;
    in.truth.push_back(n);
  }
  return in;
}

inline DiagnoseOptions options(const sim::SimResult& r, const std::string& model) {
  DiagnoseOptions o;
  o.model = est::options_from_kfgins(r.kfgins);
  o.model.model = model;
  return o;
}

// The effect name of a spec "NAME=..." .
inline std::string effect_name(const std::string& spec) { return spec.substr(0, spec.find('=')); }

}  // namespace ldv::diag::testing
