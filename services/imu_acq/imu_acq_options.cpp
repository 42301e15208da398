#include "services/imu_acq/imu_acq_options.hpp"

#include <numbers>

#include "common/config/config_section.hpp"
#include "common/formats/kfgins_config.hpp"
#include "common/io/input_error.hpp"

namespace ldv::imu {

ImuAcqOptions load_imu_acq_options(const std::string& path) {
  using config::Range;
  ImuAcqOptions o;
  o.input.serial.baud = 460800;
  if (path.empty()) return o;
  config::ConfigSection y = config::ConfigSection::load(path);
  o.bus_url = y.text("bus_url", o.bus_url);
  config::ConfigSection input = y.section("input");
  o.input = io::byte_source_options_from(input, o.input);
  if (o.input.type == "tcp") input.fail("type", "expected serial or file for an IMU, found tcp");
  const std::string protocol = y.choice("protocol", "tsu", {"tsu", "gx2"});
  o.protocol = protocol == "gx2" ? DeviceProtocol::kGx2 : DeviceProtocol::kTsu;
  // A counter slower than 1 kHz cannot tell 100 Hz samples apart; 0 or NaN made every stamp NaN.
  const Range counter_rate_hz = Range::between(1e3, 1e10);
  o.tsu_counter_hz = y.section("tsu").number("counter_hz", o.tsu_counter_hz, counter_rate_hz);
  config::ConfigSection g = y.section("gx2");
  o.gx2_timer_hz = g.number("timer_hz", o.gx2_timer_hz, counter_rate_hz);
  o.gx2_continuous_record = static_cast<int>(g.integer("continuous_record", o.gx2_continuous_record, 0, 0xFF));
  o.sample_rate_hz = y.number("sample_rate_hz", o.sample_rate_hz, Range::above(0.0).up_to(5000.0));
  config::ConfigSection p = y.section("pps");
  const std::string source = p.choice("source", "device", {"device", "kernel", "none"});
  o.pps_source = source == "kernel" ? PpsSource::kKernel : source == "none" ? PpsSource::kNone : PpsSource::kDevice;
  o.kernel_pps_device = p.text("kernel_device", o.kernel_pps_device);
  const std::string side = p.choice("label_refers", "auto", {"auto", "last_pulse", "next_pulse"});
  o.label_side = side == "last_pulse" ? LabelSide::kLastPulse : side == "next_pulse" ? LabelSide::kNextPulse : LabelSide::kAuto;
  o.stamper.matcher.max_label_delay_s =
      p.number("max_label_delay_s", o.stamper.matcher.max_label_delay_s, Range::above(0.0).below(1.0));
  config::ConfigSection f = y.section("fit");
  auto& fit = o.stamper.fit;
  fit.window_edges = static_cast<std::size_t>(f.integer("window_edges", static_cast<long long>(fit.window_edges), 2, 10000));
  fit.edges_to_lock = static_cast<std::size_t>(
      f.integer("edges_to_lock", static_cast<long long>(fit.edges_to_lock), 2, static_cast<long long>(fit.window_edges)));
  fit.edge_tolerance_s = f.number("edge_tolerance_s", fit.edge_tolerance_s, Range::above(0.0).below(0.5));
  fit.acquisition_frequency_tolerance_ppm =
      f.number("acquisition_tolerance_ppm", fit.acquisition_frequency_tolerance_ppm, Range::above(0.0).up_to(1e5));
  fit.locked_frequency_tolerance_ppm =
      f.number("locked_tolerance_ppm", fit.locked_frequency_tolerance_ppm, Range::above(0.0).up_to(1e5));
  o.stamper.gps_minus_utc_s = y.number("gps_minus_utc_s", o.stamper.gps_minus_utc_s, Range::between(0.0, 60.0));
  o.hist_bin_s = y.section("timing").number("hist_bin_s", o.hist_bin_s, Range::above(0.0).below(1.0));
  if (y.has("mounting_rpy_deg")) {
    // Roll pitch yaw of the device in the body frame.
    const auto v = y.numbers("mounting_rpy_deg", {0, 0, 0}, 3, Range::between(-360.0, 360.0));
    constexpr double kDeg = std::numbers::pi / 180.0;
    o.correction.C_device_to_body = C_b_n_from_euler(Vec3(v[0], v[1], v[2]) * kDeg);
  }
  const std::string calibration = y.text("calibration_file", "");
  if (!calibration.empty()) o.calibration_file = resolve_data_path(calibration, path);
  if (!o.calibration_file.empty()) {
    try {
      o.calibration = calib::load_calibration(o.calibration_file);
    } catch (const InputError& e) {  // names the calibration file, line and key; say which setting led there
      y.fail("calibration_file", e.what());
    }
    o.correction.set_calibration(*o.calibration);
  }
  o.fit_state_file = y.text("fit_state_file", o.fit_state_file);
  o.fit_state_max_age_s = y.number("fit_state_max_age_s", o.fit_state_max_age_s, Range::above(0.0));
  config::ConfigSection c = y.section("channels");
  o.imu_channel = c.channel("imu", o.imu_channel);
  o.pps_channel = c.channel("pps", o.pps_channel);
  o.timing_channel = c.channel("timing", o.timing_channel);
  o.label_channel = c.channel("labels", o.label_channel);
  y.refuse_unknown();
  return o;
}

}  // namespace ldv::imu
