// write_outputs: every file `ldv sim` produces, written into a temporary directory beside the
// destination and moved into place only when all of them are complete.
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>

#include "common/formats/kfgins_files.hpp"
#include "common/formats/odometer_text.hpp"
#include "common/formats/rtklib_pos_writer.hpp"
#include "common/io/input_error.hpp"
#include "common/io/output_file.hpp"
#include "sim/device_streams.hpp"
#include "sim/effects.hpp"
#include "sim/random.hpp"
#include "sim/simulator.hpp"
#include "sim/vehicle_realism.hpp"

namespace ldv::sim {
namespace {
namespace fs = std::filesystem;

void write_truth_nav(const std::string& path, const SimResult& r) {
  NavWriter w(path);
  for (const TruthSample& s : r.truth) w.write(NavRecord{r.request.gps_week, s.t_s, s.pos, s.vel_n_mps, s.rpy_rad});
}

YAML::Node flow(const std::vector<double>& v) {
  YAML::Node n(YAML::NodeType::Sequence);
  for (double x : v) n.push_back(x);
  n.SetStyle(YAML::EmitterStyle::Flow);
  return n;
}

// The individual road bumps and GNSS outliers (when those effects are on).
void write_vehicle_events(YAML::Emitter& e, const SimResult& r) {
  const double t0 = r.request.start_sow_s;
  if (r.realism.shocks_per_km > 0.0) {
    e << YAML::Key << "shock_events"
      << YAML::Comment(
             "t_sow [s], duration [s], roll rate peak, pitch rate peak [deg/s] (vehicle x, y), "
             "vertical accel peak [m/s^2] (vehicle z, down +): sim/road_shocks.hpp");
    e << YAML::Value << YAML::BeginSeq;
    for (const ShockEvent& s : r.shocks)
      e << flow({t0 + s.t_start_s, s.duration_s, s.roll_rate_peak_rad_s * kRadToDeg,
                 s.pitch_rate_peak_rad_s * kRadToDeg, s.vertical_accel_peak_mps2});
    e << YAML::EndSeq;
  }
  if (r.realism.gnss_outlier_rate > 0.0) {
    e << YAML::Key << "gnss_outlier_events" << YAML::Comment("t_sow [s], position jump N E D [m]");
    e << YAML::Value << YAML::BeginSeq;
    for (const GnssOutlier& o : r.gnss_outliers)
      e << flow({o.t_s, o.offset_ned_m.x(), o.offset_ned_m.y(), o.offset_ned_m.z()});
    e << YAML::EndSeq;
  }
}

// The answer key: every injected effect in SI and in the engineering units of the command line.
void write_truth_effects(const std::string& path, const SimResult& r) {
  const SimRequest& q = r.request;
  YAML::Emitter e;
  e.SetDoublePrecision(12);
  e << YAML::BeginMap;
  e << YAML::Key << "simulator" << YAML::Value << YAML::BeginMap;
  e << YAML::Key << "grade" << YAML::Value << (q.custom_grade ? q.custom_grade->name : q.grade);
  e << YAML::Key << "grade_source" << YAML::Value << r.grade_source;
  e << YAML::Key << "seed" << YAML::Value << q.seed;
  e << YAML::Key << "scenario" << YAML::Value << q.scenario;
  e << YAML::Key << "duration_s" << YAML::Value << q.duration_s;
  e << YAML::Key << "imu_rate_hz" << YAML::Value << q.imu_rate_hz;
  e << YAML::Key << "gnss_rate_hz" << YAML::Value << q.gnss_rate_hz;
  e << YAML::Key << "gnss_mode" << YAML::Value << q.gnss_mode;
  e << YAML::Key << "with_noise" << YAML::Value << q.with_noise;
  e << YAML::Key << "gps_week" << YAML::Value << q.gps_week;
  e << YAML::Key << "start_sow_s" << YAML::Value << q.start_sow_s;
  e << YAML::Key << "outages" << YAML::Value << YAML::BeginSeq;
  for (const Outage& o : q.outages) e << flow({o.start_s, o.length_s});
  e << YAML::EndSeq;
  if (r.realism.realism_vehicle) e << YAML::Key << "realism" << YAML::Value << q.vehicle.realism;
  e << YAML::EndMap;
  e << YAML::Key << "effects" << YAML::Comment("true injected values; si: SI units (docs/effects.md)");
  e << YAML::Value << YAML::BeginMap;
  for (const auto& [name, si] : r.injected_effects) {
    e << YAML::Key << name << YAML::Value << YAML::BeginMap;
    e << YAML::Key << "si" << YAML::Value << flow(si);
    const EffectInfo* info = find_effect(name);
    if (!info) info = find_realism_quantity(name);
    if (info && info->si_per_unit.size() >= si.size()) {
      std::vector<double> eng;
      std::string units;
      for (size_t i = 0; i < si.size(); ++i) {
        eng.push_back(si[i] / info->si_per_unit[i]);
        units += (i ? "," : "") + info->units[i];
      }
      e << YAML::Key << "value" << YAML::Value << flow(eng);
      e << YAML::Key << "unit" << YAML::Value << units;
    }
    const bool declared =
        std::find(r.declared_effects.begin(), r.declared_effects.end(), name) != r.declared_effects.end();
    e << YAML::Key << "declared" << YAML::Value << declared;
    e << YAML::EndMap;
  }
  e << YAML::EndMap;
  write_vehicle_events(e, r);
  e << YAML::EndMap;
  std::ofstream out(path);
  if (!out) throw InputError(path, 0, "cannot open file for writing");
  out << "# ldv sim: the truth of every injected effect (the answer key for ldv diagnose)\n" << e.c_str() << "\n";
  close_checked(out, path);
}

void write_truth_errors(const std::string& path, const SimResult& r) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) throw InputError(path, 0, "cannot open file for writing");
  std::fprintf(f, "# total true IMU bias (constant + moving parts) at 1 Hz\n"
                  "# sow[s] gyro_bias_x y z [rad/s] accel_bias_x y z [m/s^2]\n");
  for (const auto& b : r.imu_bias_history)
    std::fprintf(f, "%.6f %.9e %.9e %.9e %.9e %.9e %.9e\n", b.t_s, b.gyro_bias_rad_s.x(), b.gyro_bias_rad_s.y(),
                 b.gyro_bias_rad_s.z(), b.accel_bias_mps2.x(), b.accel_bias_mps2.y(), b.accel_bias_mps2.z());
  close_checked(f, path);
}

void write_bytes(const std::string& path, const void* data, size_t n) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) throw InputError(path, 0, "cannot open file for writing");
  const size_t w = std::fwrite(data, 1, n, f);
  close_checked(f, path);
  if (w != n) throw InputError(path, 0, "write error");
}

void write_device_files(const fs::path& dir, const SimResult& r) {
  const SimRequest& q = r.request;
  Oscillator osc;
  osc.nominal_hz = q.oscillator_hz;
  osc.ppm = q.oscillator_ppm;
  Rng phase(q.seed, "oscillator_phase");
  osc.phase_counts = std::floor(phase.uniform() * 4294967296.0);
  const DeviceStreams d = make_device_streams(r.imu, q.start_sow_s, q.gps_week, r.gnss, r.gnss_latency_s,
                                              q.gnss_rate_hz, q.gnss_latency_s, q.leap_seconds, osc, q.seed,
                                              q.with_noise);
  write_bytes((dir / "imu_device.bin").string(), d.imu_bytes.data(), d.imu_bytes.size());
  write_bytes((dir / "gnss.nmea").string(), d.nmea_text.data(), d.nmea_text.size());
  const std::string sched = (dir / "device_schedule.txt").string();
  std::FILE* f = std::fopen(sched.c_str(), "wb");
  if (!f) throw InputError(sched, 0, "cannot open file for writing");
  std::fprintf(f, "# when each chunk of the device streams leaves the device (replay pacing)\n"
                  "# oscillator: %.1f Hz nominal, %+.3f ppm, counter at start %.0f, latch jitter %.0f ns\n"
                  "# sow[s] stream(0=imu_device.bin,1=gnss.nmea) byte_offset length\n",
               osc.nominal_hz, osc.ppm, osc.phase_counts, osc.latch_jitter_s * 1e9);
  for (const auto& s : d.schedule)
    std::fprintf(f, "%.9f %d %llu %llu\n", s.t_sow_s, s.stream, static_cast<unsigned long long>(s.offset),
                 static_cast<unsigned long long>(s.length));
  close_checked(f, sched);
}

// What a new user writes from the datasheet: the same files and noise of the grade, no initial state
// (the system aligns from the data), no lever arm, no time offset, no estimator settings.
KfGinsConfig datasheet_config(const SimResult& r) {
  KfGinsConfig c;
  c.imu_path = r.kfgins.imu_path;
  c.gnss_path = r.kfgins.gnss_path;
  c.output_path = r.kfgins.output_path;
  c.config_path = r.kfgins.config_path;
  c.imu_data_columns = r.kfgins.imu_data_columns;
  c.imu_rate_hz = r.kfgins.imu_rate_hz;
  c.start_time_s = r.kfgins.start_time_s;
  c.end_time_s = -1.0;
  c.imu_noise = r.kfgins.imu_noise;
  c.init_gyro_bias_std_rad_s = r.kfgins.init_gyro_bias_std_rad_s;  // the datasheet's turn-on bias
  c.init_accel_bias_std_mps2 = r.kfgins.init_accel_bias_std_mps2;
  YAML::Node ldv;
  ldv["week"] = r.request.gps_week;
  if (r.kfgins.ldv["odopath"]) ldv["odopath"] = r.kfgins.ldv["odopath"].as<std::string>();
  c.ldv = ldv;
  return c;
}

void write_all(const fs::path& tmp, const fs::path& final_dir, SimResult& r) {
  const SimRequest& q = r.request;
  r.kfgins.imu_path = (final_dir / "imu.txt").string();
  r.kfgins.gnss_path = (final_dir / "gnss.txt").string();
  r.kfgins.output_path = final_dir.string();
  r.kfgins.config_path = (final_dir / "kfgins.yaml").string();
  write_kfgins_imu((tmp / "imu.txt").string(), r.imu);
  write_kfgins_gnss((tmp / "gnss.txt").string(), r.gnss, q.gnss_velocity);
  write_truth_nav((tmp / "truth.nav").string(), r);
  r.kfgins.ldv["week"] = q.gps_week;  // KF-GINS has no week: `ldv nav` reads ldv.week for its .nav
  if (r.realism.odometer) {
    write_odometer_text((tmp / "odo.txt").string(), r.odometer);
    r.kfgins.ldv["odopath"] = (final_dir / "odo.txt").string();
  }
  save_kfgins_config(r.kfgins, (tmp / "kfgins.yaml").string());
  if (r.realism.write_datasheet_config) save_kfgins_config(datasheet_config(r), (tmp / "datasheet.yaml").string());
  write_truth_effects((tmp / "truth_effects.yaml").string(), r);
  write_truth_errors((tmp / "truth_errors.txt").string(), r);
  RtklibPosOptions pos;
  pos.gps_week = q.gps_week;
  pos.program = "ldvnav ldv sim (simulated RTK solution)";
  pos.comments = {"scenario  : " + r.scenario_name, "gnss mode : " + q.gnss_mode};
  pos.with_velocity = q.gnss_velocity;
  write_rtklib_pos((tmp / "gnss.pos").string(), r.gnss, pos);
  write_device_files(tmp, r);
}
}  // namespace

void write_outputs(SimResult& result, const std::string& out_dir) {
  if (out_dir.empty()) throw InputError("--out", 0, "expected an output directory");
  const fs::path final_dir = fs::absolute(out_dir).lexically_normal();
  const fs::path parent = final_dir.has_filename() ? final_dir.parent_path() : final_dir.parent_path().parent_path();
  const fs::path target = final_dir.has_filename() ? final_dir : final_dir.parent_path();
  std::error_code ec;
  fs::create_directories(parent, ec);
  if (ec) throw InputError(out_dir, 0, "cannot create the parent directory: " + ec.message());
  if (fs::exists(target) && !fs::is_directory(target))
    throw InputError(out_dir, 0, "expected a directory, found an existing file");
  std::random_device rd;
  const fs::path tmp = parent / ("." + target.filename().string() + ".partial-" + std::to_string(rd()));
  fs::create_directory(tmp, ec);
  if (ec) throw InputError(out_dir, 0, "cannot create a temporary directory beside it: " + ec.message());
  try {
    write_all(tmp, target, result);
    if (!fs::exists(target)) {
      fs::rename(tmp, target);
    } else {  // keep other files in an existing directory; replace ours one by one (atomic renames)
      for (const auto& entry : fs::directory_iterator(tmp)) fs::rename(entry.path(), target / entry.path().filename());
      fs::remove(tmp);
    }
  } catch (...) {
    fs::remove_all(tmp, ec);
    throw;
  }
}

}  // namespace ldv::sim
