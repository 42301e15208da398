// `ldv sim`: simulate a vehicle run (truth, IMU, GNSS, device streams) into a directory.
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <limits>
#include <memory>

#include "common/io/input_error.hpp"
#include "sim/effects.hpp"
#include "sim/imu_grade.hpp"
#include "sim/scenario.hpp"
#include "sim/simulator.hpp"
#include "tools/ldv/cli_checks.hpp"
#include "tools/ldv/command_registry.hpp"

namespace {
using namespace ldv;

struct SimOptions {
  sim::SimRequest req;
  std::string outages_text;
  std::string out_dir;
  std::vector<double> lever_arm;
  // Vehicle options (sim/vehicle_realism.hpp): given or not decides whether the realism preset draws them.
  double imu_stamp_jitter = 0;
  double vibration = 0, shocks = 0, imu_latency = 0, gnss_velocity_lag = 0, gnss_velocity_noise = 0, gnss_outliers = 0;
  std::vector<double> mounting, engine_vibration, odo_lever_arm;
  bool no_noise = false;
  bool quiet = false;
  bool list_scenarios = false, list_effects = false;
  std::string print_scenario, print_grade;
};

std::vector<sim::Outage> parse_outages(const std::string& text) {
  std::vector<sim::Outage> out;
  size_t pos = 0;
  while (pos < text.size()) {
    const size_t comma = std::min(text.find(',', pos), text.size());
    const std::string item = text.substr(pos, comma - pos);
    const size_t colon = item.find(':');
    try {
      if (colon == std::string::npos) throw std::invalid_argument("no colon");
      size_t used1 = 0, used2 = 0;
      const std::string a = item.substr(0, colon), b = item.substr(colon + 1);
      const double start = std::stod(a, &used1), length = std::stod(b, &used2);
      if (used1 != a.size() || used2 != b.size()) throw std::invalid_argument("trailing text");
      out.push_back({start, length});
    } catch (const std::exception&) {
      throw InputError("--outages", 0, "expected START:LENGTH[,START:LENGTH...] in seconds, found '" + item + "'");
    }
    pos = comma + 1;
  }
  return out;
}

// Copies the vehicle options that were given (an option not given stays unset: the preset may draw it).
void set_vehicle_options(SimOptions& o, const CLI::App& cmd) {
  auto& v = o.req.vehicle;
  auto given = [&](const char* name) { return cmd.get_option(name)->count() > 0; };
  if (given("--vibration")) v.vibration_factor = o.vibration;
  if (given("--shocks")) v.shocks_per_km = o.shocks;
  if (given("--imu-latency")) v.imu_latency_s = o.imu_latency;
  if (given("--imu-stamp-jitter")) v.imu_stamp_jitter_s = o.imu_stamp_jitter;
  if (given("--gnss-velocity-lag")) v.gnss_velocity_lag_s = o.gnss_velocity_lag;
  if (given("--gnss-velocity-noise")) v.gnss_velocity_noise_factor = o.gnss_velocity_noise;
  if (given("--gnss-outliers")) v.gnss_outlier_rate = o.gnss_outliers;
  if (!o.mounting.empty()) {
    if (o.mounting.size() != 3) throw InputError("--mounting", 0, "expected 3 values roll,pitch,yaw [deg]");
    v.mounting_rpy_deg = Vec3(o.mounting[0], o.mounting[1], o.mounting[2]);
  }
  if (!o.engine_vibration.empty()) {
    if (o.engine_vibration.size() != 2)
      throw InputError("--engine-vibration", 0, "expected 2 values ACCEL_MPS2,GYRO_DPS");
    v.engine_accel_mps2 = o.engine_vibration[0];
    v.engine_gyro_dps = o.engine_vibration[1];
  }
  if (!o.odo_lever_arm.empty()) {
    if (o.odo_lever_arm.size() != 3) throw InputError("--odo-lever-arm", 0, "expected 3 values x,y,z [m]");
    v.odo_lever_arm_b_m = Vec3(o.odo_lever_arm[0], o.odo_lever_arm[1], o.odo_lever_arm[2]);
  }
}

void run(SimOptions& o, const CLI::App& cmd) {
  if (o.list_scenarios) {
    for (const auto& n : sim::builtin_scenario_names()) {
      const auto s = sim::load_scenario(n);
      std::printf("%-11s %s\n", n.c_str(), s.description.c_str());
    }
    return;
  }
  if (o.list_effects) {
    for (const auto& e : sim::effect_table()) {
      std::string units, defaults;
      for (size_t i = 0; i < e.units.size(); ++i) units += (i ? "," : "") + e.units[i];
      for (size_t i = 0; i < e.defaults.size(); ++i) defaults += (i ? "," : "") + std::to_string(e.defaults[i]);
      std::printf("%-22s [%s] default %s\n    %s\n", e.name.c_str(), units.c_str(), defaults.c_str(), e.meaning.c_str());
    }
    std::printf("%-22s gyro_moving_bias and accel_moving_bias with their defaults\n", "moving_bias");
    return;
  }
  if (!o.print_scenario.empty()) {
    const std::string text = sim::builtin_scenario_yaml(o.print_scenario);
    if (text.empty()) throw InputError("--print-scenario", 0, "unknown built-in scenario '" + o.print_scenario + "'");
    std::fputs(text.c_str(), stdout);
    return;
  }
  if (!o.print_grade.empty()) {
    const std::string text = sim::builtin_grade_yaml(o.print_grade);
    if (text.empty()) {
      std::string names;
      for (const auto& n : sim::imu_grade_names())
        if (!sim::builtin_grade_yaml(n).empty()) names += (names.empty() ? "" : ", ") + n;
      throw InputError("--print-grade", 0,
                       "no file form of the grade '" + o.print_grade + "': expected one of " + names +
                           " (the paper's grades; perfect and the -typical stand-ins have no file form)");
    }
    std::fputs(text.c_str(), stdout);
    return;
  }
  if (o.out_dir.empty()) throw InputError("--out", 0, "expected an output directory (--out DIR)");
  if (!o.outages_text.empty()) o.req.outages = parse_outages(o.outages_text);
  if (!o.lever_arm.empty()) {
    if (o.lever_arm.size() != 3) throw InputError("--lever-arm", 0, "expected 3 values x,y,z [m]");
    const std::string spec = "lever_arm=" + std::to_string(o.lever_arm[0]) + "," + std::to_string(o.lever_arm[1]) +
                             "," + std::to_string(o.lever_arm[2]);
    sim::parse_effect(spec, "--lever-arm");  // its bounds, named as the user gave them
    o.req.effects.push_back(spec);
  }
  o.req.with_noise = !o.no_noise;
  set_vehicle_options(o, cmd);
  int last_percent = -1;
  auto progress = [&](double f) {
    const int p = static_cast<int>(f * 100.0);
    if (o.quiet || p == last_percent) return;
    last_percent = p;
    std::fprintf(stderr, "\rldv sim: %3d%%", p);
    if (p >= 100) std::fprintf(stderr, "\n");
  };
  sim::SimResult r = sim::simulate(o.req, progress);
  if (!o.quiet) std::fprintf(stderr, "ldv sim: writing %s\n", o.out_dir.c_str());
  sim::write_outputs(r, o.out_dir);
  std::printf("scenario %s, grade %s, seed %llu: %zu IMU samples, %zu GNSS fixes, %zu effects injected -> %s\n",
              r.scenario_name.c_str(), o.req.grade.c_str(), static_cast<unsigned long long>(o.req.seed), r.imu.size(),
              r.gnss.size(), r.injected_effects.size(), r.kfgins.output_path.c_str());
}

void add_sim_command(CLI::App& app) {
  auto opts = std::make_shared<SimOptions>();
  CLI::App* cmd = app.add_subcommand("sim", "simulate a vehicle run: truth, IMU increments, GNSS, device streams");
  auto& r = opts->req;
  r.scenario = "drive";
  cmd->add_option("--grade", r.grade,
                  "IMU grade: perfect | hg1700 | hg1900 | 3dm-gx2 | 3dm-gx2-q-arcsec (the paper's Tables 4-9; "
                  "aliases hg1700-paper, hg1900-paper, 3dm-gx2-paper, 3dm-gx2-paper-q-arcsec) | hg1700-typical | "
                  "hg1900-typical | 3dm-gx2-typical (datasheet stand-ins with typical in-run terms), or a grade YAML "
                  "file in the paper's units (sim/README.md; --print-grade NAME shows the keys)")
      ->capture_default_str();
  cmd->add_option("--seed", r.seed, "random seed (same seed, same data)")
      ->capture_default_str()
      ->check(CLI::Range(std::uint64_t{0}, std::numeric_limits<std::uint64_t>::max()));
  cmd->add_option("--duration", r.duration_s, "run length [s]")
      ->capture_default_str()
      ->check(ldv::cli::checked_where_used());
  cmd->add_option("--scenario", r.scenario, "built-in scenario name or YAML file (--list-scenarios)")->capture_default_str();
  cmd->add_option("--imu-rate", r.imu_rate_hz, "IMU rate [Hz]")
      ->capture_default_str()
      ->check(ldv::cli::checked_where_used());
  cmd->add_option("--gnss-rate", r.gnss_rate_hz, "GNSS rate [Hz]")
      ->capture_default_str()
      ->check(ldv::cli::checked_where_used());
  cmd->add_option("--effect", r.effects, "inject an effect: NAME or NAME=v1,v2,v3 (engineering units, --list-effects); hidden unless declared");
  cmd->add_option("--declare", r.declared_effects, "inject an effect and also write it into kfgins.yaml (NAME or NAME=values)");
  cmd->add_option("--outages", opts->outages_text, "GNSS outages START:LENGTH,... [s from the run start]");
  cmd->add_option("--lever-arm", opts->lever_arm, "shorthand for --effect lever_arm=x,y,z [m]")
      ->delimiter(',')
      ->expected(3)
      ->check(ldv::cli::checked_where_used());
  cmd->add_option("--gnss-mode", r.gnss_mode, "GNSS solution type: fixed | float | single")->capture_default_str();
  cmd->add_flag("--gnss-velocity", r.gnss_velocity, "write 13-column gnss.txt with velocity");
  cmd->add_option("--gnss-latency", r.gnss_latency_s, "mean GNSS solution latency [s]")
      ->capture_default_str()
      ->check(ldv::cli::checked_where_used());
  cmd->add_option("--gps-week", r.gps_week, "GPS week of the run")
      ->capture_default_str()
      ->check(ldv::cli::checked_where_used());
  cmd->add_option("--start-sow", r.start_sow_s, "start time [s of GPS week]")
      ->capture_default_str()
      ->check(ldv::cli::checked_where_used());
  cmd->add_option("--osc-hz", r.oscillator_hz, "time-stamp unit counter frequency [Hz]")
      ->capture_default_str()
      ->check(ldv::cli::checked_where_used());
  cmd->add_option("--osc-ppm", r.oscillator_ppm, "counter frequency error [ppm]")
      ->capture_default_str()
      ->check(ldv::cli::checked_where_used());
  cmd->add_option("--leap-seconds", r.leap_seconds, "GPS - UTC [s] for NMEA times")
      ->capture_default_str()
      ->check(ldv::cli::finite_range(0, 100));
  auto& v = r.vehicle;
  cmd->add_option("--realism", v.realism,
                  "none | vehicle: vibration, shocks, IMU latency, mounting, GNSS velocity lag and outliers, odometer, "
                  "datasheet.yaml (options given explicitly win)")
      ->capture_default_str();
  cmd->add_option("--vibration", opts->vibration,
                  "vehicle vibration: installed white noise = FACTOR x the grade's ARW/VRW, plus engine harmonics")
      ->check(ldv::cli::checked_where_used());
  cmd->add_option("--engine-vibration", opts->engine_vibration,
                  "engine harmonic amplitudes with --vibration: ACCEL_MPS2,GYRO_DPS (default 0.3,0.2)")
      ->delimiter(',')
      ->expected(2)
      ->check(ldv::cli::checked_where_used());
  cmd->add_option("--shocks", opts->shocks, "road bumps per km travelled")->check(ldv::cli::checked_where_used());
  cmd->add_option("--imu-latency", opts->imu_latency, "IMU time tags late by S [s] (tag = true time + S)")
      ->check(ldv::cli::checked_where_used());
  cmd->add_option("--imu-stamp-jitter", opts->imu_stamp_jitter,
                  "IMU time tags scattered about the sample times by a std of S [s] (uniform; a host that tags on "
                  "reading), each increment the sample's rate over its tag interval")
      ->check(ldv::cli::checked_where_used());
  cmd->add_option("--mounting", opts->mounting,
                  "IMU body in the vehicle: roll,pitch,yaw [deg], C_b_v = Rz(yaw) Ry(pitch) Rx(roll)")
      ->delimiter(',')
      ->expected(3)
      ->check(ldv::cli::checked_where_used());
  cmd->add_option("--gnss-velocity-lag", opts->gnss_velocity_lag, "GNSS velocity is the one at epoch - S [s]")
      ->check(ldv::cli::checked_where_used());
  cmd->add_option("--gnss-velocity-noise", opts->gnss_velocity_noise,
                  "simulated GNSS velocity noise = FACTOR x the stated std (the stated std unchanged)")
      ->check(ldv::cli::checked_where_used());
  cmd->add_option("--gnss-outliers", opts->gnss_outliers, "fraction of GNSS epochs with a 1-3 m position jump")
      ->check(ldv::cli::checked_where_used());
  cmd->add_flag("--odometer", v.odometer, "write odo.txt: sow, forward speed [m/s]");
  cmd->add_option("--odo-rate", v.odo_rate_hz, "odometer rate [Hz]")
      ->capture_default_str()
      ->check(ldv::cli::checked_where_used());
  cmd->add_option("--odo-lever-arm", opts->odo_lever_arm,
                  "odometer point (rear-axle centre) minus IMU, x,y,z [m] in IMU body axes")
      ->delimiter(',')
      ->expected(3)
      ->check(ldv::cli::checked_where_used());
  cmd->add_option("--odo-noise", v.odo_noise_mps, "odometer white noise std [m/s]")
      ->capture_default_str()
      ->check(ldv::cli::checked_where_used());
  cmd->add_option("--odo-quantum", v.odo_quantum_mps, "odometer speed resolution [m/s] (0: none)")
      ->capture_default_str()
      ->check(ldv::cli::checked_where_used());
  cmd->add_option("--wheel-slip", v.wheel_slip_deg_per_mps2,
                  "side slip on turns [deg per m/s^2 of lateral acceleration], drifting to the outside")
      ->check(ldv::cli::checked_where_used());
  cmd->add_flag("--no-noise", opts->no_noise, "no random noise (sensor and GNSS); deterministic errors stay");
  cmd->add_option("--out", opts->out_dir, "output directory (written all-or-nothing)");
  cmd->add_flag("--quiet", opts->quiet, "no progress on stderr");
  cmd->add_flag("--list-scenarios", opts->list_scenarios, "list the built-in scenarios and exit");
  cmd->add_flag("--list-effects", opts->list_effects, "list the effects, units and defaults and exit");
  cmd->add_option("--print-scenario", opts->print_scenario, "print a built-in scenario's YAML and exit");
  cmd->add_option("--print-grade", opts->print_grade, "print a built-in grade's YAML (the paper's units) and exit");
  cmd->callback([opts, cmd] { run(*opts, *cmd); });
}

const ldv::cli::RegisterCommand kRegisterSimCommand{"sim", &add_sim_command};
}  // namespace
