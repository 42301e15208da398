#pragma once
// imu_acq's configuration (deploy/config/imu_acq.yaml).
#include <optional>
#include <string>

#include "services/input/byte_source_options.hpp"
#include "services/imu_acq/imu_correction.hpp"
#include "services/imu_acq/imu_time_stamper.hpp"

namespace ldv::imu {

enum class DeviceProtocol { kTsu, kGx2 };
enum class PpsSource {
  kDevice,  // PPS latch frames in the device stream (time-stamp unit)
  kKernel,  // /dev/ppsN; samples are then stamped by their host arrival time (no device latch)
  kNone,    // no PPS: every stamp is extrapolated and flagged
};
enum class LabelSide { kAuto, kLastPulse, kNextPulse };  // auto: from GNSS_PPS flags bit 3

struct ImuAcqOptions {
  std::string bus_url;
  io::ByteSourceOptions input;
  DeviceProtocol protocol = DeviceProtocol::kTsu;
  double tsu_counter_hz = 10e6;
  double gx2_timer_hz = 19660800.0;
  int gx2_continuous_record = 0xC3;  // sent as "set continuous mode" on each open; 0: send nothing
  double sample_rate_hz = 100.0;     // nominal, for the first interval and the histogram
  PpsSource pps_source = PpsSource::kDevice;
  std::string kernel_pps_device = "/dev/pps0";
  LabelSide label_side = LabelSide::kAuto;
  StamperOptions stamper;
  double hist_bin_s = 2e-7;
  ImuCorrection correction;  // mounting_rpy_deg, and the calibration below
  // `ldv calib static` output, loaded into `correction` (a relative path: from the working directory, else
  // beside the configuration file; stored resolved).
  std::string calibration_file;
  std::optional<calib::ImuCalibration> calibration;
  // The PPS fit saved across restarts (fit_state.hpp; "": not saved); a saved fit older than the maximum
  // age is not used (oscillator drift and a cold device make it worthless).
  std::string fit_state_file;
  double fit_state_max_age_s = 600.0;
  std::string imu_channel = "IMU", pps_channel = "IMU_PPS", timing_channel = "IMU_TIMING",
              label_channel = "GNSS_PPS";
};

// Throws config::ConfigError (a std::runtime_error) naming the file, line and key on a bad or unknown key
// (for the calibration file: both files).
ImuAcqOptions load_imu_acq_options(const std::string& path);

}  // namespace ldv::imu
