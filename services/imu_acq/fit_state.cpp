#include "services/imu_acq/fit_state.hpp"

#include <cmath>
#include <sstream>

#include <yaml-cpp/yaml.h>

#include "common/io/atomic_file.hpp"

namespace ldv::imu {

void save_fit_state(const std::string& path, const FitState& s) {
  std::ostringstream out;
  out.precision(17);
  out << "saved_host_time_s: " << s.saved_host_time_s << "\n"
      << "counter: " << s.counter << "\n"
      << "gps_total_s: " << s.gps_total_s << "\n"
      << "counter_hz: " << s.counter_hz << "\n"
      << "counter_bits: " << s.counter_bits << "\n";
  write_file_atomically(path, out.str());
}

std::optional<FitState> load_fit_state(const std::string& path, double now_host_s, double max_age_s) {
  try {
    const YAML::Node y = YAML::LoadFile(path);
    FitState s;
    s.saved_host_time_s = y["saved_host_time_s"].as<double>();
    s.counter = y["counter"].as<std::int64_t>();
    s.gps_total_s = y["gps_total_s"].as<double>();
    s.counter_hz = y["counter_hz"].as<double>();
    s.counter_bits = y["counter_bits"].as<int>();
    const double age_s = now_host_s - s.saved_host_time_s;
    if (age_s > max_age_s || age_s < -1.0) return std::nullopt;
    if (!(s.counter_hz > 0.0) || !std::isfinite(s.gps_total_s) || s.counter_bits < 8 || s.counter_bits > 64)
      return std::nullopt;
    return s;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

}  // namespace ldv::imu
