// `ldv outage`: GNSS outages inserted during manoeuvres, the paper's Table 12 and the KF-GINS metric.
//   ldv outage --kfgins-config FILE.yaml [--truth truth.nav] [--lengths 60,120,300,600] [--json OUT.json]
// Takes every input `ldv nav` takes, plus the real walk's layout (--imu-csv/--imu-tag/--pos).
#include <cstdio>
#include <fstream>
#include <memory>

#include "common/formats/kfgins_files.hpp"
#include "common/io/input_error.hpp"
#include "toolbox/assess/nav_inputs.hpp"
#include "toolbox/assess/outage_run.hpp"
#include "toolbox/assess/outage_table.hpp"
#include "tools/ldv/command_registry.hpp"

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
  const assess::OutageRun run = assess::run_outages(in.imu, in.gnss, in.config, in.options, truth, a.run);
  const auto summary = assess::summarise_outages(run);
  assess::print_outage_table(stdout, run, summary);
  std::printf("\n%zu outages on %d threads: uncut run %.1f s, outages %.1f s (%ld IMU samples)\n", run.outages.size(),
              run.threads, run.uncut_run_s, run.outages_run_s, run.imu_samples);
  if (!a.json.empty()) {
    std::ofstream f(a.json);
    if (!f) throw InputError(a.json, 0, "cannot open file for writing");
    f << assess::outage_json(run, summary);
  }
}

// The input options of `ldv nav`, plus the tagged-CSV / RTKLIB layout of the real walk.
void add_nav_input_options(CLI::App* c, assess::NavInputArgs& in) {
  c->add_option("--kfgins-config", in.config, "KF-GINS YAML configuration (as ldv nav)");
  c->add_option("--imu", in.imu, "IMU increments (KF-GINS imu.txt), overrides the config");
  c->add_option("--gnss", in.gnss, "GNSS solutions (KF-GINS gnss.txt), overrides the config");
  c->add_option("--imu-csv", in.imu_csv, "tagged IMU CSV (ax,ay,az [g], gx,gy,gz [deg/s], counter [ms])");
  c->add_option("--imu-tag", in.imu_tag, "RTKLIB time-tag file of --imu-csv");
  c->add_option("--csv-axes", in.csv_axes, "device axes to front-right-down, e.g. 1 -2 -3 (default 1 2 3)")->expected(3);
  c->add_option("--pos", in.rtklib_pos, "GNSS solutions as an RTKLIB .pos file");
  c->add_option("--model", in.model, "ins15 | kfgins21 | geoldv51");
  c->add_option("--add", in.add, "add an effect block (repeatable)");
  c->add_option("--drop", in.drop, "drop an effect block (repeatable)");
  c->add_option("--lever", in.lever, "antenna lever arm x y z [m], body front-right-down")->expected(3);
}

void add_outage_command(CLI::App& app) {
  auto a = std::make_shared<OutageArgs>();
  CLI::App* c = app.add_subcommand("outage", "GNSS outages during manoeuvres: drift table (paper Table 12) and KF-GINS metric");
  add_nav_input_options(c, a->inputs);
  c->add_option("--truth", a->truth, "truth .nav (else the drift is measured against the uncut solution)");
  c->add_option("--lengths", a->run.lengths_s, "outage lengths [s]")->delimiter(',');
  c->add_option("--json", a->json, "write every outage, its drift curve and the table as JSON");
  c->add_option("--converge", a->run.plan.converge_s, "no outage in the first seconds of GNSS [s]");
  c->add_option("--recovery", a->run.plan.recovery_s, "GNSS kept between outages [s]");
  c->add_option("--manoeuvre-accel", a->run.plan.manoeuvre_accel_mps2, "horizontal acceleration of a manoeuvre [m/s^2]");
  c->add_option("--min-speed", a->run.plan.min_speed_mps, "an outage starts only when moving faster [m/s]");
  c->add_option("--threads", a->run.threads, "worker threads (0: all cores)");
  c->add_flag("--exact", a->run.exact_rerun, "re-run the whole filter per outage instead of restarting from checkpoints (slow)");
  c->add_flag("--no-zupt", a->no_zupt, "no zero-velocity updates (in the uncut run and the outages)");
  c->add_flag("--quiet", a->quiet, "no progress on stderr");
  c->callback([a] { run_outage(*a); });
}

const ldv::cli::RegisterCommand kRegister{"outage", &add_outage_command};
}  // namespace
