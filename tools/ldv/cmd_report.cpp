// `ldv report ... --out DIR`: DIR/index.html (self-contained page) and its PNGs (gnuplot): trajectory,
// errors or differences with 3-sigma envelopes, innovations, outage drift, Allan deviation, diagnosis.
#include <cstdio>
#include <memory>

#include "toolbox/assess/report_sections.hpp"
#include "tools/ldv/cli_checks.hpp"
#include "tools/ldv/command_registry.hpp"

namespace {
using namespace ldv;

struct ReportArgs {
  assess::ReportInputs in;
  std::string out;
};

void add_report_command(CLI::App& app) {
  auto a = std::make_shared<ReportArgs>();
  CLI::App* c = app.add_subcommand("report", "HTML report with plots (gnuplot) of a run, its outages, Allan deviation, diagnosis");
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
    const std::string index = assess::write_report(a->in, a->out);
    std::printf("%s\n", index.c_str());
  });
}

const ldv::cli::RegisterCommand kRegisterReportCommand{"report", &add_report_command};
}  // namespace
