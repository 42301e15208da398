// `ldv report ... --out DIR`: DIR/index.html (self-contained page) and its PNGs (gnuplot): trajectory,
// errors or differences with 3-sigma envelopes, innovations, outage drift, Allan deviation, diagnosis.
// `ldv report --kfgins-config F [--truth T] --out DIR`: one command from a configuration alone; it runs what the page
// needs (ldv nav or ldv smooth, ldv outage, ldv diagnose) into DIR, each as the user would run it, with a progress
// line, and reuses an output that is newer than the configuration and the data it names.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/formats/kfgins_config.hpp"
#include "common/io/run_program.hpp"
#include "toolbox/assess/report_sections.hpp"
#include "tools/ldv/cli_checks.hpp"
#include "tools/ldv/command_registry.hpp"

namespace {
using namespace ldv;
namespace fs = std::filesystem;

struct ReportArgs {
  assess::ReportInputs in;
  std::string out, config;
  bool smooth = false, no_outage = false, no_diagnose = false;
};

// This program, to run its own commands as the user would.
std::string self_path() {
  std::error_code ec;
  const fs::path p = fs::read_symlink("/proc/self/exe", ec);
  return ec ? std::string("ldv") : p.string();
}

// An output is up to date when it is newer than the configuration and every data file it names.
bool up_to_date(const fs::path& output, const std::vector<std::string>& sources) {
  std::error_code ec;
  if (!fs::is_regular_file(output, ec) || fs::file_size(output, ec) == 0) return false;
  const auto t = fs::last_write_time(output, ec);
  for (const std::string& s : sources) {
    if (s.empty()) continue;
    const auto ts = fs::last_write_time(s, ec);
    if (ec || ts > t) return false;
  }
  return true;
}

// The last non-empty line of a log: what a failed step said.
std::string last_line(const fs::path& log) {
  std::ifstream f(log);
  std::string line, last;
  while (std::getline(f, line))
    if (!line.empty()) last = line;
  return last;
}

// Runs `ldv ARGS` for one step of the page (no shell: the user's paths stay arguments), its output in DIR/<name>.log;
// false (said) when it failed.
bool run_step(int index, int steps, const std::string& what, std::vector<std::string> args, const fs::path& output,
              const std::vector<std::string>& sources, const fs::path& dir, const std::string& name) {
  if (up_to_date(output, sources)) {
    std::fprintf(stderr, "ldv report: [%d/%d] %s: %s is up to date, reused\n", index, steps, what.c_str(),
                 output.c_str());
    return true;
  }
  std::fprintf(stderr, "ldv report: [%d/%d] %s ...\n", index, steps, what.c_str());
  const auto t0 = std::chrono::steady_clock::now();
  const fs::path log = dir / (name + ".log");
  args.insert(args.begin(), self_path());
  const int rc = run_program(args, ".", log, log);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (rc != 0) {
    std::fprintf(stderr, "ldv report: [%d/%d] %s failed after %.1f s, its section is left out: %s (log %s)\n", index,
                 steps, what.c_str(), s, last_line(log).c_str(), log.c_str());
    return false;
  }
  std::fprintf(stderr, "ldv report: [%d/%d] %s done in %.1f s\n", index, steps, what.c_str(), s);
  return true;
}

void run_from_config(ReportArgs& a) {
  const KfGinsConfig cfg = load_kfgins_config(a.config);  // refused here, naming the file and line, if it is wrong
  const fs::path dir = a.out;
  fs::create_directories(dir);
  std::vector<std::string> sources = {a.config, cfg.imu_path, cfg.gnss_path, a.in.truth};
  // a step's arguments with the configuration, and the truth where it takes one and one is given
  const auto with_inputs = [&](std::vector<std::string> args, bool takes_truth) {
    args.insert(args.end(), {"--kfgins-config", a.config});
    if (takes_truth && !a.in.truth.empty()) args.insert(args.end(), {"--truth", a.in.truth});
    return args;
  };
  const int steps = 1 + !a.no_outage + !a.no_diagnose;
  int k = 0;
  const fs::path nav = dir / "run.nav";
  if (!run_step(++k, steps, a.smooth ? "smoothing (ldv smooth)" : "navigation (ldv nav)",
                with_inputs({a.smooth ? "smooth" : "nav", "--out", nav.string()}, false), nav, sources, dir, "nav"))
    throw std::runtime_error("report: the navigation failed: nothing to show (log " + (dir / "nav.log").string() + ")");
  a.in.nav = nav.string();
  if (!a.no_outage) {
    const fs::path json = dir / "outage.json";
    if (run_step(++k, steps, "GNSS-outage study (ldv outage)", with_inputs({"outage", "--json", json.string()}, true),
                 json, sources, dir, "outage"))
      a.in.outage_json = json.string();
  }
  if (!a.no_diagnose) {
    const fs::path json = dir / "diagnose.json";
    if (run_step(++k, steps, "diagnosis (ldv diagnose)", with_inputs({"diagnose", "--json", json.string()}, true), json,
                 sources, dir, "diagnose"))
      a.in.diagnose_json = json.string();
  }
}

void add_report_command(CLI::App& app) {
  auto a = std::make_shared<ReportArgs>();
  CLI::App* c = app.add_subcommand("report", "HTML report with plots (gnuplot) of a run, its outages, Allan deviation, diagnosis");
  c->add_option("--kfgins-config", a->config,
                "run what the page needs from this configuration (ldv nav or smooth, outage, diagnose) into --out, "
                "reusing outputs newer than the configuration and its data");
  c->add_flag("--smooth", a->smooth, "with --kfgins-config: the smoothed solution (ldv smooth) instead of ldv nav's");
  c->add_flag("--no-outage", a->no_outage, "with --kfgins-config: no GNSS-outage study");
  c->add_flag("--no-diagnose", a->no_diagnose, "with --kfgins-config: no diagnosis");
  c->add_option("--nav", a->in.nav, "solution (.nav; its _std.txt and _innovations.txt are used when beside it)");
  c->add_option("--truth", a->in.truth, "truth or reference solution (.nav)");
  c->add_option("--reference-label", a->in.reference_label, "what --truth is called on the page (default truth)");
  c->add_option("--std", a->in.std_file, "ldv nav's _std.txt");
  c->add_option("--innovations", a->in.innovations, "ldv nav's _innovations.txt");
  c->add_option("--forward", a->in.forward,
                "with a smoothed --nav: the forward solution (default FILE_forward.nav beside it, as ldv smooth writes)");
  c->add_option("--separation", a->in.separation,
                "with a smoothed --nav: ldv smooth's _separation.txt (default beside it)");
  c->add_option("--outage-json", a->in.outage_json, "ldv outage --json output");
  c->add_option("--allan-json", a->in.allan_json, "ldv allan --json output");
  c->add_option("--allan-loop-json", a->in.allan_loop_json,
                "ldv allan --json runs of one record with growing --terms (e.g. QNBK then QNBKR), in order: the "
                "stochastic model loop (the misfit per decade names the missing term, adding it makes it fall)");
  c->add_option("--diagnose-json", a->in.diagnose_json, "ldv diagnose --json output");
  c->add_option("--settle", a->in.settle_s, "skip the first seconds in error statistics and plots [s]")
      ->check(ldv::cli::finite_range(0, 1e7));
  c->add_option("--title", a->in.title, "page title");
  c->add_option("--out", a->out, "output directory (index.html and PNGs)")->required();
  c->callback([a] {
    if (!a->config.empty() && a->in.nav.empty()) run_from_config(*a);
    const std::string index = assess::write_report(a->in, a->out);
    std::printf("%s\n", index.c_str());
  });
}

const ldv::cli::RegisterCommand kRegisterReportCommand{"report", &add_report_command};
}  // namespace
