#pragma once
// Simulated drives shared by the assessment tests (cached per request: each is made once per process).
#include <map>
#include <string>
#include <tuple>

#include "sim/simulator.hpp"
#include "toolbox/assess/nav_series.hpp"

namespace ldv::test {

inline const sim::SimResult& sim_drive(const std::string& grade, double duration_s, const std::string& scenario = "drive",
                                       const std::vector<std::string>& effects = {}, bool noise = true, uint64_t seed = 7) {
  static std::map<std::string, sim::SimResult> cache;
  std::string key = grade + "|" + std::to_string(duration_s) + "|" + scenario + "|" + std::to_string(noise) + "|" + std::to_string(seed);
  for (const auto& e : effects) key += "|" + e;
  auto it = cache.find(key);
  if (it == cache.end()) {
    sim::SimRequest r;
    r.grade = grade;
    r.duration_s = duration_s;
    r.scenario = scenario;
    r.effects = effects;
    r.with_noise = noise;
    r.seed = seed;
    it = cache.emplace(key, sim::simulate(r)).first;
  }
  return it->second;
}

inline assess::NavSeries truth_series(const sim::SimResult& s) {
  std::vector<assess::NavSample> v;
  v.reserve(s.truth.size());
  for (const auto& t : s.truth) v.push_back({t.t_s, t.pos, t.vel_n_mps, quat_from_euler(t.rpy_rad)});
  return assess::NavSeries(std::move(v));
}

}  // namespace ldv::test
