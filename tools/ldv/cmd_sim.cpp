// `ldv sim`: simulate a vehicle run (truth, IMU, GNSS, device streams) into a directory.
#include <cstdio>
#include <iostream>
#include <memory>

#include "common/io/input_error.hpp"
#include "sim/effects.hpp"
#include "sim/imu_grade.hpp"
#include "sim/scenario.hpp"
#include "sim/simulator.hpp"
#include "tools/ldv/command_registry.hpp"

namespace {
using namespace ldv;

struct SimOptions {
  sim::SimRequest req;
  std::string outages_text;
  std::string out_dir;
  std::vector<double> lever_arm;
  bool no_noise = false;
  bool quiet = false;
  bool list_scenarios = false, list_effects = false;
  std::string print_scenario;
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

void run(SimOptions& o) {
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
  if (o.out_dir.empty()) throw InputError("--out", 0, "expected an output directory (--out DIR)");
  if (!o.outages_text.empty()) o.req.outages = parse_outages(o.outages_text);
  if (!o.lever_arm.empty()) {
    if (o.lever_arm.size() != 3) throw InputError("--lever-arm", 0, "expected 3 values x,y,z [m]");
    o.req.effects.push_back("lever_arm=" + std::to_string(o.lever_arm[0]) + "," + std::to_string(o.lever_arm[1]) + "," +
                            std::to_string(o.lever_arm[2]));
  }
  o.req.with_noise = !o.no_noise;
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
  cmd->add_option("--grade", r.grade, "IMU grade: perfect | hg1700 | hg1900 | 3dm-gx2")->capture_default_str();
  cmd->add_option("--seed", r.seed, "random seed (same seed, same data)")->capture_default_str();
  cmd->add_option("--duration", r.duration_s, "run length [s]")->capture_default_str();
  cmd->add_option("--scenario", r.scenario, "built-in scenario name or YAML file (--list-scenarios)")->capture_default_str();
  cmd->add_option("--imu-rate", r.imu_rate_hz, "IMU rate [Hz]")->capture_default_str();
  cmd->add_option("--gnss-rate", r.gnss_rate_hz, "GNSS rate [Hz]")->capture_default_str();
  cmd->add_option("--effect", r.effects, "inject an effect: NAME or NAME=v1,v2,v3 (engineering units, --list-effects); hidden unless declared");
  cmd->add_option("--declare", r.declared_effects, "inject an effect and also write it into kfgins.yaml (NAME or NAME=values)");
  cmd->add_option("--outages", opts->outages_text, "GNSS outages START:LENGTH,... [s from the run start]");
  cmd->add_option("--lever-arm", opts->lever_arm, "shorthand for --effect lever_arm=x,y,z [m]")->delimiter(',')->expected(3);
  cmd->add_option("--gnss-mode", r.gnss_mode, "GNSS solution type: fixed | float | single")->capture_default_str();
  cmd->add_flag("--gnss-velocity", r.gnss_velocity, "write 13-column gnss.txt with velocity");
  cmd->add_option("--gnss-latency", r.gnss_latency_s, "mean GNSS solution latency [s]")->capture_default_str();
  cmd->add_option("--gps-week", r.gps_week, "GPS week of the run")->capture_default_str();
  cmd->add_option("--start-sow", r.start_sow_s, "start time [s of GPS week]")->capture_default_str();
  cmd->add_option("--osc-hz", r.oscillator_hz, "time-stamp unit counter frequency [Hz]")->capture_default_str();
  cmd->add_option("--osc-ppm", r.oscillator_ppm, "counter frequency error [ppm]")->capture_default_str();
  cmd->add_option("--leap-seconds", r.leap_seconds, "GPS - UTC [s] for NMEA times")->capture_default_str();
  cmd->add_flag("--no-noise", opts->no_noise, "no random noise (sensor and GNSS); deterministic errors stay");
  cmd->add_option("--out", opts->out_dir, "output directory (written all-or-nothing)");
  cmd->add_flag("--quiet", opts->quiet, "no progress on stderr");
  cmd->add_flag("--list-scenarios", opts->list_scenarios, "list the built-in scenarios and exit");
  cmd->add_flag("--list-effects", opts->list_effects, "list the effects, units and defaults and exit");
  cmd->add_option("--print-scenario", opts->print_scenario, "print a built-in scenario's YAML and exit");
  cmd->callback([opts] { run(*opts); });
}

const ldv::cli::RegisterCommand kRegister{"sim", &add_sim_command};
}  // namespace
