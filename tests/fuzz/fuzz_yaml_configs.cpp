// The YAML configurations (a KF-GINS file with its ldv: section, imu_acq's and gnss_link's): whatever the text,
// a clear error naming the file (InputError, ConfigError) or a configuration whose numbers are finite. Any other
// exception (a raw yaml-cpp error without the file) is a finding.
#include <cmath>

#include "common/config/config_section.hpp"
#include "common/formats/kfgins_config.hpp"
#include "common/io/input_error.hpp"
#include "services/gnss_link/gnss_link_options.hpp"
#include "services/imu_acq/imu_acq_options.hpp"
#include "tests/fuzz/fuzz_support.hpp"

using namespace ldv;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const std::string path = fuzz::input_file(data + 1, size - 1, "config.yaml");
  try {
    switch (data[0] % 3) {
      case 0: {
        const KfGinsConfig c = load_kfgins_config(path);
        fuzz::require(std::isfinite(c.imu_rate_hz) && c.imu_rate_hz > 0 && std::isfinite(c.start_time_s) &&
                          std::isfinite(c.end_time_s) && c.imu_noise.arw_rad_per_sqrt_s.allFinite() &&
                          c.imu_noise.gyro_bias_std_rad_s.allFinite() && std::isfinite(c.imu_noise.corr_time_s),
                      "a KF-GINS configuration with a number not finite");
        if (c.init_rpy_rad) fuzz::require(c.init_rpy_rad->allFinite(), "initatt not finite");
        break;
      }
      case 1:
        imu::load_imu_acq_options(path);
        break;
      case 2:
        gnss::load_gnss_link_options(path);
        break;
    }
  } catch (const InputError&) {
  } catch (const config::ConfigError&) {
  } catch (const std::exception& e) {
    fuzz::finding(std::string("an error that names no file: ") + e.what());
  }
  return 0;
}
