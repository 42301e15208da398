#include "services/imu_acq/imu_acq_options.hpp"

#include <numbers>
#include <stdexcept>

#include <yaml-cpp/yaml.h>

#include "common/formats/kfgins_config.hpp"
#include "common/io/input_error.hpp"

namespace ldv::imu {

ImuAcqOptions load_imu_acq_options(const std::string& path) {
  ImuAcqOptions o;
  o.input.serial.baud = 460800;
  if (path.empty()) return o;
  const YAML::Node y = YAML::LoadFile(path);
  auto fail = [&](const std::string& what) { throw std::runtime_error(path + ": " + what); };
  if (y["bus_url"]) o.bus_url = y["bus_url"].as<std::string>();
  const int default_baud = o.input.serial.baud;
  o.input = io::byte_source_options_from_yaml(y["input"], path);
  if (!(y["input"] && y["input"]["serial"] && y["input"]["serial"]["baud"])) o.input.serial.baud = default_baud;
  if (o.input.type == "tcp") fail("input.type tcp is not supported for an IMU (serial or file)");
  if (y["protocol"]) {
    const auto p = y["protocol"].as<std::string>();
    if (p == "tsu") o.protocol = DeviceProtocol::kTsu;
    else if (p == "gx2") o.protocol = DeviceProtocol::kGx2;
    else fail("protocol must be tsu or gx2, not '" + p + "'");
  }
  if (y["tsu"] && y["tsu"]["counter_hz"]) o.tsu_counter_hz = y["tsu"]["counter_hz"].as<double>();
  if (const auto g = y["gx2"]) {
    if (g["timer_hz"]) o.gx2_timer_hz = g["timer_hz"].as<double>();
    if (g["continuous_record"]) o.gx2_continuous_record = g["continuous_record"].as<int>();
  }
  if (y["sample_rate_hz"]) o.sample_rate_hz = y["sample_rate_hz"].as<double>();
  if (const auto p = y["pps"]) {
    if (p["source"]) {
      const auto s = p["source"].as<std::string>();
      if (s == "device") o.pps_source = PpsSource::kDevice;
      else if (s == "kernel") o.pps_source = PpsSource::kKernel;
      else if (s == "none") o.pps_source = PpsSource::kNone;
      else fail("pps.source must be device, kernel or none, not '" + s + "'");
    }
    if (p["kernel_device"]) o.kernel_pps_device = p["kernel_device"].as<std::string>();
    if (p["label_refers"]) {
      const auto s = p["label_refers"].as<std::string>();
      if (s == "auto") o.label_side = LabelSide::kAuto;
      else if (s == "last_pulse") o.label_side = LabelSide::kLastPulse;
      else if (s == "next_pulse") o.label_side = LabelSide::kNextPulse;
      else fail("pps.label_refers must be auto, last_pulse or next_pulse");
    }
    if (p["max_label_delay_s"]) o.stamper.matcher.max_label_delay_s = p["max_label_delay_s"].as<double>();
  }
  if (const auto f = y["fit"]) {
    auto& fit = o.stamper.fit;
    if (f["window_edges"]) fit.window_edges = f["window_edges"].as<std::size_t>();
    if (f["edges_to_lock"]) fit.edges_to_lock = f["edges_to_lock"].as<std::size_t>();
    if (f["edge_tolerance_s"]) fit.edge_tolerance_s = f["edge_tolerance_s"].as<double>();
    if (f["acquisition_tolerance_ppm"]) fit.acquisition_frequency_tolerance_ppm = f["acquisition_tolerance_ppm"].as<double>();
    if (f["locked_tolerance_ppm"]) fit.locked_frequency_tolerance_ppm = f["locked_tolerance_ppm"].as<double>();
  }
  if (y["gps_minus_utc_s"]) o.stamper.gps_minus_utc_s = y["gps_minus_utc_s"].as<double>();
  if (y["timing"] && y["timing"]["hist_bin_s"]) o.hist_bin_s = y["timing"]["hist_bin_s"].as<double>();
  if (y["mounting_rpy_deg"]) {
    const auto v = y["mounting_rpy_deg"].as<std::vector<double>>();
    if (v.size() != 3) fail("mounting_rpy_deg needs 3 values (roll pitch yaw of the device in the body frame)");
    constexpr double kDeg = std::numbers::pi / 180.0;
    o.correction.C_device_to_body = C_b_n_from_euler(Vec3(v[0], v[1], v[2]) * kDeg);
  }
  if (const auto c = y["calibration_file"]; c && !c.IsNull()) {
    if (!c.IsScalar()) fail("calibration_file must be a path (\"\": none)");
    o.calibration_file = resolve_data_path(c.Scalar(), path);
  }
  if (!o.calibration_file.empty()) {
    try {
      o.calibration = calib::load_calibration(o.calibration_file);
    } catch (const InputError& e) {  // names the calibration file, line and key; say which setting led there
      fail("calibration_file: " + std::string(e.what()));
    }
    o.correction.set_calibration(*o.calibration);
  }
  if (const auto c = y["fit_state_file"]; c && !c.IsNull()) {
    if (!c.IsScalar()) fail("fit_state_file must be a path (\"\": none)");
    o.fit_state_file = c.Scalar();
  }
  if (y["fit_state_max_age_s"]) o.fit_state_max_age_s = y["fit_state_max_age_s"].as<double>();
  if (!(o.fit_state_max_age_s > 0)) fail("fit_state_max_age_s must be > 0");
  if (const auto c = y["channels"]) {
    if (c["imu"]) o.imu_channel = c["imu"].as<std::string>();
    if (c["pps"]) o.pps_channel = c["pps"].as<std::string>();
    if (c["timing"]) o.timing_channel = c["timing"].as<std::string>();
    if (c["labels"]) o.label_channel = c["labels"].as<std::string>();
  }
  if (o.sample_rate_hz <= 0 || o.sample_rate_hz > 5000) fail("sample_rate_hz must be in (0, 5000]");
  if (o.hist_bin_s <= 0) fail("timing.hist_bin_s must be > 0");
  return o;
}

}  // namespace ldv::imu
