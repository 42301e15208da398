// `ldv outage`: GNSS outages inserted during manoeuvres, the paper's Table 12 and the KF-GINS metric.
//   ldv outage --kfgins-config FILE.yaml [--truth truth.nav] [--lengths 60,120,300,600] [--json OUT.json]
// Takes every input `ldv nav` takes, plus the real walk's layout (--imu-csv/--imu-tag/--pos).
#include <cstdio>
#include <fstream>
#include <memory>

#include "common/formats/kfgins_files.hpp"
#include "common/io/input_error.hpp"
#include "common/io/output_file.hpp"
#include "toolbox/assess/nav_inputs.hpp"
#include "toolbox/assess/outage_run.hpp"
#include "toolbox/assess/outage_table.hpp"
#include "tools/ldv/cli_checks.hpp"
#include "tools/ldv/command_registry.hpp"
#include "tools/ldv/nav_input_options.hpp"

namespace {
using namespace ldv;

struct OutageArgs {
  assess::NavInputArgs inputs;
  std::string truth, json;
  assess::OutageRunOptions run;
  bool quiet = false, no_zupt = false;
};

void run_outage(OutageArgs& a) {
  assess::NavInputs in = assess::load_nav_inputs(a.inputs);
  if (a.no_zupt) in.options.zupt.enabled = false;
  assess::NavSeries truth;
  if (!a.truth.empty()) truth = assess::NavSeries::from_records(read_nav(a.truth));
  if (!a.quiet) {
    std::fprintf(stderr, "ldv outage: %zu IMU samples, %zu GNSS fixes (%s)\n", in.imu.size(), in.gnss.size(),
                 in.description.c_str());
    a.run.progress = [](const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); };
  }
  assess::OutageRunOptions run_options = a.run;
  run_options.others = in.other_observations;
  const assess::OutageRun run = assess::run_outages(in.imu, in.gnss, in.config, in.options, truth, run_options);
  const auto summary = assess::summarise_outages(run);
  assess::print_outage_table(stdout, run, summary);
  std::printf("\n%zu outages on %d threads: uncut run %.1f s, outages %.1f s (%ld IMU samples)\n", run.outages.size(),
              run.threads, run.uncut_run_s, run.outages_run_s, run.imu_samples);
  for (const assess::OutageWindow& w : run.unmeasured)
    std::printf("not measured: the %.0f s outage from %.3f s (the %s has no sample at its end)\n", w.length_s,
                w.start_s, run.reference.c_str());
  if (!a.json.empty()) {
    std::ofstream f(a.json);
    if (!f) throw InputError(a.json, 0, "cannot open file for writing");
    f << assess::outage_json(run, summary);
    ldv::close_checked(f, a.json);
  }
}

void add_outage_command(CLI::App& app) {
  auto a = std::make_shared<OutageArgs>();
  CLI::App* c = app.add_subcommand("outage", "GNSS outages during manoeuvres: drift table (paper Table 12) and KF-GINS metric");
  cli::add_nav_input_options(c, a->inputs);
  c->add_option("--truth", a->truth, "truth .nav (else the drift is measured against the uncut solution)");
  c->add_option("--lengths", a->run.lengths_s, "outage lengths [s]")->delimiter(',')->check(cli::finite_positive(1e7));
  c->add_option("--json", a->json, "write every outage, its drift curve and the table as JSON");
  c->add_option("--converge", a->run.plan.converge_s, "no outage in the first seconds of GNSS [s]")->check(cli::finite_range(0, 1e7));
  c->add_option("--recovery", a->run.plan.recovery_s, "GNSS kept between outages [s]")->check(cli::finite_range(0, 1e7));
  c->add_option("--manoeuvre-accel", a->run.plan.manoeuvre_accel_mps2, "horizontal acceleration of a manoeuvre [m/s^2]")
      ->check(cli::finite_range(0, 1e3));
  c->add_option("--min-speed", a->run.plan.min_speed_mps, "an outage starts only when moving faster [m/s]")->check(cli::finite_range(0, 1e3));
  c->add_option("--threads", a->run.threads, "worker threads (0: all cores; at most 256 are used)")->check(CLI::Range(0, 100000));
  c->add_flag("--exact", a->run.exact_rerun, "re-run the whole filter per outage instead of restarting from checkpoints (slow)");
  c->add_flag("--smooth", a->run.smooth,
              "also smooth (forward + RTS backward; per length one run with all its gaps cut): the largest smoothed "
              "error inside each gap");
  c->add_flag("--no-zupt", a->no_zupt, "no zero-velocity updates (in the uncut run and the outages)");
  c->add_flag("--quiet", a->quiet, "no progress on stderr");
  c->callback([a] { run_outage(*a); });
}

const ldv::cli::RegisterCommand kRegisterOutageCommand{"outage", &add_outage_command};
}  // namespace
