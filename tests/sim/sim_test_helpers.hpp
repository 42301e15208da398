#pragma once
// Small helpers shared by the simulator tests.
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "common/geo/earth_model.hpp"
#include "common/io/input_error.hpp"
#include "sim/simulator.hpp"

namespace ldv::sim::test {

inline std::filesystem::path temp_dir(const std::string& name) {
  const auto p = std::filesystem::temp_directory_path() / ("ldv_sim_test_" + name);
  std::filesystem::remove_all(p);
  return p;
}

inline std::string write_text(const std::string& name, const std::string& text) {
  const auto p = std::filesystem::temp_directory_path() / ("ldv_sim_test_" + name);
  std::ofstream(p) << text;
  return p.string();
}

// The message of the InputError thrown by f, or "" when nothing was thrown.
inline std::string input_error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// A noiseless, error-free request on a scenario.
inline SimRequest perfect_request(const std::string& scenario, double duration_s, double imu_rate_hz = 100.0) {
  SimRequest r;
  r.grade = "perfect";
  r.scenario = scenario;
  r.duration_s = duration_s;
  r.imu_rate_hz = imu_rate_hz;
  r.with_noise = false;
  return r;
}

// NED vector from a to b through exact ECEF geometry (independent of the simulator's first-order helpers).
inline Vec3 exact_ned(const Geodetic& a, const Geodetic& b) {
  return earth::C_n_e(a).transpose() * (earth::ecef_from_geodetic(b) - earth::ecef_from_geodetic(a));
}

}  // namespace ldv::sim::test
