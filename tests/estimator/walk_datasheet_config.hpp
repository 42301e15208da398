#pragma once
// Test helper: the real walk in ../shared (walk_0827: a hand-held MEMS unit with its own RTK antenna) configured as
// a new user would from the IMU's datasheet alone (no tuning keys, no lever arm, no initial state): the drive
// nobody tuned the self-calibration to.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "toolbox/assess/nav_inputs.hpp"

namespace ldv::est::test {

// Writes the configuration to a file of its own in the temp directory and returns its path (the caller removes it).
inline std::filesystem::path write_walk_datasheet_config(const std::string& name) {
  const std::string walk = std::string(LDV_SHARED_DATA_DIR) + "/drives/walk_0827/";
  const std::filesystem::path config =
      std::filesystem::temp_directory_path() / ("ldv_walk_" + name + "_" + std::to_string(::getpid()) + ".yaml");
  std::ofstream(config) << "imupath: " << walk << "imu_1730.csv\ngnsspath: " << walk << "gnss_1730_sf.pos\n"
                        << "outputpath: .\nimudatalen: 7\nimudatarate: 150\nstarttime: 0\nendtime: -1\n"
                        << "imunoise:\n  arw: [0.24, 0.24, 0.24]\n  vrw: [0.06, 0.06, 0.06]\n"
                        << "  gbstd: [10, 10, 10]\n  abstd: [200, 200, 200]\n  gsstd: [1000, 1000, 1000]\n"
                        << "  asstd: [1000, 1000, 1000]\n  corrtime: 1\nantlever: [0, 0, 0]\n"
                        << "ldv:\n  pos_height_offset_m: 21.387\n";
  return config;
}

// The walk as `ldv nav --kfgins-config` reads it from that configuration (imu_time_shift_s: --imu-time-shift).
inline assess::NavInputs walk_datasheet_inputs(const std::string& name,
                                               double imu_time_shift_s = assess::NavInputArgs::kUnset) {
  const std::filesystem::path config = write_walk_datasheet_config(name);
  assess::NavInputArgs a;
  a.config = config.string();
  a.imu_time_shift_s = imu_time_shift_s;
  assess::NavInputs in = assess::load_nav_inputs(a);
  std::filesystem::remove(config);
  return in;
}

}  // namespace ldv::est::test
