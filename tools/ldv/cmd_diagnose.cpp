// `ldv diagnose`: compare the model with the measurements, see where it fails, find the missing
// physical effect, add it, watch the error fall (DESIGN.md section 3; toolbox/diagnose/README.md).
//   ldv diagnose --kfgins-config FILE.yaml [--model NAME] [--add EFFECT]... [--drop EFFECT]...
//                [--json OUT.json] [--truth truth.nav] [--plots DIR] [--iterate] [--write-config TUNED.yaml]
// Inputs as `ldv nav` takes them from files (KF-GINS text, tagged IMU CSV, RTKLIB .pos).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>

#include "common/formats/kfgins_config.hpp"
#include "common/formats/kfgins_files.hpp"
#include "common/io/atomic_file.hpp"
#include "common/io/input_error.hpp"
#include "estimator/run/effect_priors_config.hpp"
#include "estimator/run/run_navigation.hpp"
#include "toolbox/diagnose/diagnosis.hpp"
#include "toolbox/diagnose/plots.hpp"
#include "toolbox/diagnose/report_json.hpp"
#include "toolbox/diagnose/report_text.hpp"
#include "tools/ldv/cli_checks.hpp"
#include "tools/ldv/command_registry.hpp"
#include "tools/ldv/nav_input_options.hpp"

namespace {
using namespace ldv;

struct DiagnoseArgs {
  assess::NavInputArgs inputs;
  std::string json, truth, plots, write_config;
  int max_add = 3;
  bool iterate = false;
  double alpha = 0.05, bandwidth_s = 120.0;
  bool quiet = false;
};

constexpr int kMaxIterations = 12;

// The user's configuration with the verdict's effects added to ldv.add, their estimates as comments, and the
// aids and odometer file the diagnosis ran with (so the tuned run sees what the diagnosis saw).
void write_tuned_config(const std::string& config_path, const diag::Diagnosis& d, const est::AidOptions& aids,
                        const std::string& odometer_path, const std::string& out_path) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(config_path);
  } catch (const YAML::Exception& e) {
    throw InputError(config_path, e.mark.line + 1, std::string("cannot read the configuration: ") + e.what());
  }
  std::vector<std::string> add;
  if (root["ldv"] && root["ldv"]["add"]) add = root["ldv"]["add"].as<std::vector<std::string>>();
  for (const std::string& e : d.add)
    if (std::find(add.begin(), add.end(), e) == add.end()) add.push_back(e);
  root["ldv"]["add"] = add;
  // Every added effect's estimate as its prior, with its estimated sigma (ldv.priors, in the printed units): the
  // tuned run starts where the diagnosis ended, not at zero with the default prior. The mounting's residual is
  // folded into the coarse mounting below, so its prior mean is zero.
  for (const diag::EffectEstimate& e : d.added_estimates) {
    // An estimate without a finite value or sigma is left to the comment below: a prior must be a number.
    if (e.value_si.size() == 0 || e.value_si.size() != e.std_si.size() || !e.value_si.allFinite() ||
        !e.std_si.allFinite())
      continue;
    const est::PrintUnit unit = est::effect_print_unit(e.name);
    std::vector<double> value, sigma;
    for (int i = 0; i < e.value_si.size(); ++i) {
      value.push_back(e.name == "vehicle_mounting" ? 0.0 : e.value_si(i) * unit.scale);
      sigma.push_back(e.std_si(i) * unit.scale);
    }
    YAML::Node prior;
    prior["value"] = value;
    prior["sigma"] = sigma;
    prior["unit"] = unit.unit;
    root["ldv"]["priors"][e.name] = prior;
  }
  // The estimates where KF-GINS's keys or ldv's older ones have a place for them (read as before).
  for (const diag::EffectEstimate& e : d.added_estimates) {
    if (e.name == "lever_arm" && e.value_si.size() == 3)
      root["antlever"] = std::vector<double>{e.value_si(0), e.value_si(1), e.value_si(2)};
    if (e.name == "time_offset" && e.value_si.size() == 1) root["ldv"]["time_offset_s"] = e.value_si(0);
    if (e.name == "odometer_scale" && e.value_si.size() == 1) root["ldv"]["odometer_scale"] = e.value_si(0);
    if (e.name == "odometer_lever_arm" && e.value_si.size() == 3)
      root["ldv"]["odometer_lever_arm_m"] = std::vector<double>{e.value_si(0), e.value_si(1), e.value_si(2)};
    if (e.name == "vehicle_mounting" && e.value_si.size() == 3) {
      // The residual rotation goes into the coarse mounting: C_b_v = C_coarse C(mu).
      const Vec3 rpy = euler_from_C_b_n(C_b_n_from_euler(aids.mounting_rpy_rad) * C_b_n_from_euler(e.value_si.head<3>()));
      root["ldv"]["vehicle_mounting_deg"] = std::vector<double>{rpy.x() * kRadToDeg, rpy.y() * kRadToDeg, rpy.z() * kRadToDeg};
    }
  }
  // The GNSS noise a step took in: the configured factors (ldv.gnss_variance_scale, if any) times the added ones.
  if (d.gnss_noise_added) {
    const auto& k = d.final_options.gnss_variance_scale;
    root["ldv"]["gnss_variance_scale"] = std::vector<double>{k[0], k[1], k[2]};
  }
  if (!aids.enabled.empty()) root["ldv"]["aids"] = aids.enabled;
  if (!odometer_path.empty()) root["ldv"]["odopath"] = std::filesystem::absolute(odometer_path).string();
  // The white noise the diagnosis ran with: the noise as installed in place of the configured floor, and what a step
  // raised on top (PSD factors; the densities written take their square roots).
  const auto scale_white_noise = [&](double gyro_psd, double accel_psd) {
    if (!root["imunoise"]) return;
    for (const char* key : {"arw", "vrw"}) {
      if (!root["imunoise"][key] || !root["imunoise"][key].IsSequence()) continue;
      std::vector<double> v = root["imunoise"][key].as<std::vector<double>>();
      for (double& x : v) x *= std::sqrt(std::string(key) == "arw" ? gyro_psd : accel_psd);
      root["imunoise"][key] = v;
    }
  };
  if (d.imu_noise_applied) scale_white_noise(d.imu_noise_scale.gyro, d.imu_noise_scale.accel);
  if (d.imu_noise_added) scale_white_noise(d.imu_noise_added->value_si(0), d.imu_noise_added->value_si(1));
  YAML::Emitter emitter;
  emitter << root;
  std::ostringstream text;
  text << "# Tuned by `ldv diagnose` from " << config_path << ": " << d.steps.size() - 1
       << " step(s); added effects and their estimates:\n";
  for (const diag::EffectEstimate& e : d.added_estimates) {
    text << "#   " << e.name << " [" << e.unit.unit << "]:";
    for (int i = 0; i < e.value_si.size(); ++i) text << " " << e.value_si(i) * e.unit.scale;
    text << "  (1-sigma";
    for (int i = 0; i < e.std_si.size(); ++i) text << " " << e.std_si(i) * e.unit.scale;
    text << ")\n";
  }
  text << emitter.c_str() << "\n";
  if (!write_file_atomically(out_path, text.str())) throw InputError(out_path, 0, "cannot write the tuned configuration");
}

void run_diagnose(const DiagnoseArgs& a) {
  assess::NavInputArgs inputs = a.inputs;
  inputs.refine_latency_in_filter = false;  // the model under test is the user's; time_offset is the diagnosis's
  assess::NavInputs loaded = assess::load_nav_inputs(inputs);
  diag::DiagnoseInputs in;
  in.cfg = loaded.config;
  in.imu = std::move(loaded.imu);
  in.gnss = std::move(loaded.gnss);
  in.others = std::move(loaded.other_observations);
  diag::DiagnoseOptions opt;
  // The model under test: --model, else ldv.model, else the KF-GINS equivalent (kfgins21).
  opt.model = loaded.options;
  try {
    est::resolve_model(opt.model.model, opt.model.add, opt.model.drop);
  } catch (const std::invalid_argument& e) {
    throw InputError(a.inputs.config, 0, e.what());
  }
  // --iterate: add the top confirmed effect, rerun, until the model is consistent or nothing more is
  // confirmed (the stepwise search stops by itself; the cap only bounds the run time).
  opt.max_added = a.iterate ? kMaxIterations : a.max_add;
  opt.screening.alpha = a.alpha;
  opt.screening.bandwidth_s = a.bandwidth_s;
  opt.verbose = !a.quiet;
  if (!a.truth.empty()) in.truth = read_nav(a.truth);

  diag::Diagnosis d = diag::diagnose(in, opt);
  // The IMU latency the input loading looked for (and took out of the stamps when significant) is a finding of
  // the diagnosis too: a user must learn that the stamps were late, not only get a model that fits.
  if (loaded.latency.turns.valid) {
    diag::SelfCalibration c;
    c.name = "time_offset";
    // The filter pass's refinement where there was one (estimator/calibrate/drive_imu_latency.cpp).
    const bool refined = loaded.latency.refined.done;
    const double lag_s = refined ? loaded.latency.refined.lag_s : loaded.latency.turns.lag_s;
    const double sigma_s = refined ? loaded.latency.refined.sigma_s : loaded.latency.turns.sigma_s;
    c.estimate_si = Eigen::VectorXd::Constant(1, -lag_s);
    c.sigma_si = Eigen::VectorXd::Constant(1, sigma_s);
    c.unit = "ms";
    c.print_scale = 1e3;
    c.applied = loaded.latency.applied;
    // The fixes refute a lag whose pass raises -2 ln L beyond the 1-parameter test (the real walk: the turns' 406
    // ms, a hand-held unit's heading leading the walker's course).
    char refuted[160] = "";
    if (loaded.latency.refuted())
      std::snprintf(refuted, sizeof refuted,
                    "not taken out: the GNSS positions fit worse with it (-2 ln L %.1f higher): not a lag of the "
                    "stamps",
                    -loaded.latency.likelihood_gain);
    char b[320];
    std::snprintf(b, sizeof b,
                  "IMU stamps late by %.1f +- %.1f ms (the turns' heading changes against the GNSS track); %s",
                  1e3 * lag_s, 1e3 * sigma_s,
                  c.applied                       ? "taken out of the stamps before the diagnosis"
                  : *refuted                      ? refuted
                  : loaded.latency.lever_explains ? "not taken out: a forward lever arm explains the fixes as "
                                                    "well or better (the screening below weighs both)"
                                                  : "not taken out (not significant)");
    c.note = b;
    d.self_calibration.insert(d.self_calibration.begin(), c);
  }
  // Whether the GNSS velocities were fused is the system's own decision too (toolbox/assess/nav_inputs.cpp): the misfit
  // it rested on.
  if (loaded.gnss_velocity_check) {
    const est::GnssVelocityCheck& v = *loaded.gnss_velocity_check;
    diag::SelfCalibration c;
    c.name = "gnss_velocity";
    c.estimate_si = Eigen::VectorXd::Constant(1, v.normalised_mse);
    c.sigma_si = Eigen::VectorXd::Constant(1, v.normalised_mse_sigma());
    c.unit = "x its stated sigma^2 against the position chords";
    c.applied = loaded.options.use_gnss_velocity;
    c.note = loaded.gnss_velocity_note;
    d.self_calibration.push_back(c);
  }
  // The IMU tags' jitter, measured from the rows (a tagged CSV) or the increments, and modelled in every run.
  const est::ImuStampJitter& jitter =
      loaded.imu_stamp_jitter.found ? loaded.imu_stamp_jitter : d.before.summary.imu_stamp_jitter;
  if (jitter.noticeable()) {
    diag::SelfCalibration c;
    c.name = "imu_stamp_jitter";
    c.estimate_si = Eigen::VectorXd::Constant(1, jitter.sigma_s);
    c.sigma_si = Eigen::VectorXd::Constant(1, jitter.sigma_sigma_s);
    c.unit = "ms";
    c.print_scale = 1e3;
    c.applied = true;
    char b[240];
    std::snprintf(b, sizeof b,
                  "IMU tags off the sensor's %.1f Hz sampling (%.0f %% of the rows repeat the sample before): each "
                  "increment's error, the rate's change times the tag's, modelled in every run",
                  1.0 / jitter.sample_interval_s, 100.0 * jitter.repeated_fraction);
    c.note = b;
    d.self_calibration.push_back(c);
  }
  diag::print_report(std::cout, d);
  if (!a.json.empty()) diag::write_json(d, a.json);
  if (!a.write_config.empty()) {
    write_tuned_config(loaded.config.config_path, d, opt.model.aids, a.inputs.odometer, a.write_config);
    if (!a.quiet) std::cerr << "ldv diagnose: tuned configuration written to " << a.write_config << "\n";
  }
  if (!a.plots.empty()) {
    const auto written = diag::write_plots(d, a.plots);
    if (!a.quiet) std::cerr << "ldv diagnose: " << written << " plots in " << a.plots << "\n";
  }
}

void add_diagnose_command(CLI::App& app) {
  auto args = std::make_shared<DiagnoseArgs>();
  CLI::App* c = app.add_subcommand("diagnose", "find the physical effect the model is missing, add it, show the error fall");
  cli::add_nav_input_options(c, args->inputs, /*config_required=*/true);
  c->add_option("--json", args->json, "write the diagnosis as JSON");
  c->add_option("--truth", args->truth, "truth .nav (KF-GINS layout, IMU centre): navigation error before/after");
  c->add_option("--plots", args->plots, "write gnuplot PNGs (and their data and scripts) into this folder");
  c->add_option("--max-add", args->max_add, "stepwise: add at most this many effects (default 3; --iterate: until done)")->check(CLI::Range(0, 20));
  // A rate of 1 names every effect, 1e-300 none (its quantile is not finite); a bandwidth below an IMU interval or
  // beyond a week has no meaning for the GNSS errors' correlation.
  c->add_option("--alpha", args->alpha, "family-wise false-alarm rate of the screening (default 0.05)")
      ->check(cli::finite_range(1e-12, 0.5));
  c->add_option("--bandwidth", args->bandwidth_s, "long-run variance bandwidth [s] (default 120: > GNSS error correlation)")
      ->check(cli::finite_range(1e-3, 604800.0));
  c->add_flag("--iterate", args->iterate,
              "diagnose, add the top confirmed effect with its estimate, rerun, until the model is consistent or nothing "
              "more is confirmed (JSON steps and the report's step table show the fall)");
  c->add_option("--write-config", args->write_config, "write the configuration with the added effects (YAML)");
  c->add_flag("--quiet", args->quiet, "no progress on stderr");
  c->callback([args] { run_diagnose(*args); });
}

const ldv::cli::RegisterCommand kRegisterDiagnoseCommand{"diagnose", &add_diagnose_command};
}  // namespace
