// `ldv allan FILE ...`: Allan-type deviations with confidence intervals, the inertial noise terms
// (Q, N, B, K, R) with uncertainties, a table in the paper's units, JSON, KF-GINS noise and a plot.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "common/io/input_error.hpp"
#include "common/io/output_file.hpp"
#include "common/logging.hpp"
#include "tools/ldv/cli_checks.hpp"
#include "tools/ldv/command_registry.hpp"
#include "toolbox/allan/allan_input.hpp"
#include "toolbox/allan/allan_plot.hpp"
#include "toolbox/allan/allan_report.hpp"
#include "toolbox/allan/analysis.hpp"

namespace {

struct AllanArgs {
  std::string file, format, json, plot, noise_config, deviation, taus = "log", terms = "QNBKR";
  std::vector<std::string> columns, units;
  std::vector<double> counts_per_unit, tau_list;
  std::string time_column;
  double rate = 0, tau0 = 0, nominal = 0, max_tau = 0, confidence = ldv::allan::kOneSigmaConfidence;
  int per_decade = 10, threads = 0;
  std::string bias_model = "auto";
  bool gauss_markov = false, flat_bias = false, sinusoid = false, no_fit = false, curve_only = false;
  double likelihood_block_s = 0.02, target_precision = 0.1;
};

std::string guess_format(const std::string& path) {
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext == ".csv") return "csv";
  if (ext == ".phd" || ext == ".DAT" || ext == ".dat") return "phase";
  if (ext == ".frd") return "frequency";
  return "kfgins";
}

void run_allan(const AllanArgs& a) {
  using namespace ldv::allan;
  InputOptions in;
  in.format = parse_input_format(a.format.empty() ? guess_format(a.file) : a.format);
  in.rate_hz = a.rate;
  in.tau0_s = a.tau0;
  in.columns = a.columns;
  in.units = a.units;
  in.counts_per_unit = a.counts_per_unit;
  in.time_column = a.time_column;
  in.nominal = a.nominal;
  auto progress = [](const std::string& msg) { spdlog::info("allan: {}", msg); };
  spdlog::info("allan: reading {}", a.file);
  std::vector<PhaseSeries> channels = read_allan_input(a.file, in, progress);

  AnalysisOptions opt;
  try {
    opt.spacing = parse_tau_spacing(a.taus);
    if (!a.deviation.empty()) opt.extra = parse_deviation(a.deviation);
  } catch (const std::invalid_argument& e) {
    throw CLI::ValidationError(e.what());
  }
  opt.per_decade = a.per_decade;
  opt.taus_s = a.tau_list;
  opt.confidence = a.confidence;
  opt.fit = !a.no_fit;
  opt.threads = a.threads;
  if (a.max_tau > 0) opt.max_factor = static_cast<long>(a.max_tau / channels.front().tau0_s);
  FitOptions& f = opt.fit_options;
  // A letter that names no term (--terms XYZ) ran silently with none of the user's: refused by name.
  for (const char c : a.terms)
    if (std::string("QNBKR").find(c) == std::string::npos)
      throw CLI::ValidationError("--terms", std::string("'") + c + "' is not a noise term: expected letters of QNBKR "
                                 "(Q quantisation, N white noise, B bias instability, K rate random walk, R ramp)");
  f.q = a.terms.find('Q') != std::string::npos;
  f.n = a.terms.find('N') != std::string::npos;
  f.b = a.terms.find('B') != std::string::npos;
  f.k = a.terms.find('K') != std::string::npos;
  f.r = a.terms.find('R') != std::string::npos;
  // --gauss-markov / --flat-bias are shorthands of --bias-model gm / flat (CLI11 keeps them exclusive).
  const std::string bias_model = a.gauss_markov ? "gm" : a.flat_bias ? "flat" : a.bias_model;
  f.gauss_markov = bias_model == "gm";
  f.choose_bias_model = bias_model == "auto";
  f.sinusoid = a.sinusoid;
  f.likelihood = !a.curve_only;
  f.likelihood_block_s = a.likelihood_block_s;
  f.target_precision = a.target_precision;
  for (const auto& c : channels) {
    spdlog::info("allan: {} [{}]: {} samples, tau0 {} s", c.name, c.unit, c.x.size() - 1, c.tau0_s);
  }
  std::vector<ChannelResult> results;
  try {
    results = analyze(channels, opt, progress);
  } catch (const std::invalid_argument& e) {
    throw ldv::InputError(a.file, 0, e.what());
  }
  channels.clear();

  print_tables(stdout, results);
  if (opt.extra) {
    for (const auto& r : results) {
      std::printf("\n%s %s [%s]\n  %12s %8s %5s %12s %12s %12s\n", r.name.c_str(), deviation_name(*opt.extra), r.unit.c_str(),
                  "tau_s", "n", "alpha", "min", "dev", "max");
      for (const auto& p : r.extra) {
        std::printf("  %12.5g %8ld %5d %12.5e %12.5e %12.5e\n", p.point.tau_s, p.point.n_terms, p.alpha, p.interval.lo,
                    p.point.dev, p.interval.hi);
      }
    }
  }
  const std::string yaml = kfgins_noise_yaml(results);
  if (!yaml.empty()) std::printf("\n%s", yaml.c_str());
  if (!a.noise_config.empty()) {
    std::ofstream out(a.noise_config);
    if (!out) throw ldv::InputError(a.noise_config, 0, "cannot open file for writing");
    out << yaml;
    ldv::close_checked(out, a.noise_config);
    spdlog::info("allan: wrote {}", a.noise_config);
  }
  if (!a.json.empty()) {
    write_json(a.json, a.file, results, opt);
    spdlog::info("allan: wrote {}", a.json);
  }
  if (!a.plot.empty()) {
    plot_allan(a.plot, results);
    spdlog::info("allan: wrote {}", a.plot);
  }
}

void add_allan_command(CLI::App& app) {
  auto args = std::make_shared<AllanArgs>();
  CLI::App* cmd = app.add_subcommand("allan", "Allan deviation, confidence intervals and inertial noise terms");
  cmd->add_option("FILE", args->file, "input: KF-GINS imu.txt, CSV with header, or Stable32 phase/frequency data")
      ->required()->check(CLI::ExistingFile);
  cmd->add_option("--format", args->format, "kfgins | csv | phase | frequency (default from the extension: .csv csv, "
                                             ".dat/.phd phase, .frd frequency, else kfgins)")
      ->check(CLI::IsMember({"kfgins", "csv", "phase", "frequency"}));
  auto rate = cmd->add_option("--rate", args->rate, "sample rate [Hz]")->check(ldv::cli::finite_range(1e-9, 1e9));
  cmd->add_option("--tau0", args->tau0, "sample interval [s]")->check(ldv::cli::finite_range(1e-9, 1e9))->excludes(rate);
  cmd->add_option("--columns", args->columns, "csv: columns to analyse, by header name or 1-based index")->delimiter(',');
  cmd->add_option("--units", args->units,
                  "unit of the columns, one or one per column: rad/s deg/s deg/h rad/h m/s^2 g mg ug 1")->delimiter(',');
  cmd->add_option("--counts-per-unit", args->counts_per_unit,
                  "raw counts per unit (e.g. 131 for an MPU-6050 gyro in deg/s)")
      ->delimiter(',')
      ->check(ldv::cli::finite_positive(1e12));
  cmd->add_option("--time-column", args->time_column, "csv: time column [s], used for the sample interval");
  cmd->add_option("--nominal", args->nominal,
                  "frequency: values are absolute [Hz] around this nominal; analyse (f-f0)/f0")
      ->check(ldv::cli::finite_positive(1e15));
  cmd->add_option("--json", args->json, "write results (SI units) to this JSON file");
  cmd->add_option("--plot", args->plot, "write a log-log plot (PNG, via gnuplot)");
  cmd->add_option("--noise-config", args->noise_config, "write the KF-GINS imunoise YAML block to this file");
  cmd->add_option("--deviation", args->deviation, "also print a table of adev | oadev | mdev | hdev | ohdev | tdev")
      ->check(CLI::IsMember({"adev", "oadev", "mdev", "hdev", "ohdev", "tdev"}));
  cmd->add_option("--taus", args->taus, "tau spacing: all | octave | log (default log)")
      ->check(CLI::IsMember({"all", "octave", "log"}));
  cmd->add_option("--per-decade", args->per_decade, "log spacing: taus per decade (default 10)")->check(CLI::Range(1, 1000));
  cmd->add_option("--tau-list", args->tau_list, "explicit taus [s], comma separated")
      ->delimiter(',')
      ->check(ldv::cli::finite_positive(1e12));
  cmd->add_option("--max-tau", args->max_tau, "largest tau [s] (default: N/4 samples)")
      ->check(ldv::cli::finite_positive(1e12));
  cmd->add_option("--confidence", args->confidence, "confidence of the deviation intervals (default 0.683, Stable32's)")
      ->check(CLI::Range(0.01, 0.9999));
  cmd->add_option("--terms", args->terms, "noise terms to fit, any of QNBKR (default QNBKR)");
  auto bias_model =
      cmd->add_option("--bias-model", args->bias_model,
                      "bias instability model: auto | flat | gm (default auto: for rate input both the flat B and the "
                      "Gauss-Markov (sigma, T) are fitted by the likelihood and the lower AIC wins when the GM stands out "
                      "(sigma's interval off 0, T's off the white-noise bound), reported in the table and the JSON's "
                      "bias_model_selection; the flat B without the likelihood fit)")
          ->check(CLI::IsMember({"auto", "flat", "gm"}));
  auto gm_flag = cmd->add_flag("--gauss-markov", args->gauss_markov,
                               "model the bias instability as Gauss-Markov (sigma, T) instead of flat B (= --bias-model gm)")
                     ->excludes(bias_model);
  cmd->add_flag("--flat-bias", args->flat_bias, "model the bias instability as the flat B (= --bias-model flat)")
      ->excludes(bias_model)
      ->excludes(gm_flag);
  cmd->add_flag("--sinusoid", args->sinusoid, "add a sinusoidal term to the fit");
  cmd->add_flag("--no-fit", args->no_fit, "deviations only");
  cmd->add_flag("--curve-only", args->curve_only,
                "fit the Allan variance curve only (default for rate input: refine N, B, K, R by the likelihood of the raw data)");
  cmd->add_option("--likelihood-block", args->likelihood_block_s,
                  "the likelihood fit averages the rate over blocks of this length first [s]")

      ->check(ldv::cli::finite_positive(1e9));
  cmd->add_option("--target-precision", args->target_precision,
                  "report the record length at which each resolved term reaches this relative 1-sigma (default 0.1)")
      ->check(CLI::Range(1e-4, 1.0));
  cmd->add_option("--threads", args->threads, "worker threads (default: one per core; at most 256 are used)")
      ->check(CLI::Range(0, 100000));
  cmd->callback([args] { run_allan(*args); });
}

const ldv::cli::RegisterCommand kRegisterAllanCommand{"allan", &add_allan_command};

}  // namespace
