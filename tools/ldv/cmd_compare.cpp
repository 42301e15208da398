// `ldv compare A.nav B.nav [--settle S] [--json]`: the paper's Tables 10-11, A minus B (B interpolated
// at A's epochs): mean, std and RMS of E N D [m], vE vN vD [m/s], roll pitch yaw [deg].
#include <cstdio>
#include <memory>

#include "common/formats/kfgins_files.hpp"
#include "toolbox/assess/solution_comparison.hpp"
#include "tools/ldv/cli_checks.hpp"
#include "tools/ldv/command_registry.hpp"

namespace {
using namespace ldv;

struct CompareArgs {
  std::string a, b;
  assess::ComparisonOptions options;
  bool json = false;
};

void run_compare(const CompareArgs& args) {
  const auto a = assess::NavSeries::from_records(read_nav(args.a));
  const auto b = assess::NavSeries::from_records(read_nav(args.b));
  const assess::ComparisonResult r = assess::compare_solutions(a, b, args.options);
  if (args.json)
    std::printf("%s\n", assess::comparison_json(r, args.a, args.b).c_str());
  else
    assess::print_comparison(stdout, r, args.a, args.b);
}

void add_compare_command(CLI::App& app) {
  auto a = std::make_shared<CompareArgs>();
  CLI::App* c = app.add_subcommand("compare", "differences between two .nav solutions (paper Tables 10-11)");
  c->add_option("A", a->a, "solution (.nav)")->required();
  c->add_option("B", a->b, "reference solution or truth (.nav), interpolated at A's epochs")->required();
  c->add_option("--settle", a->options.settle_s, "skip A's first seconds [s]")->check(ldv::cli::finite_range(0, 1e7));
  c->add_option("--max-gap", a->options.max_gap_s, "do not interpolate B across longer gaps [s]")
      ->check(ldv::cli::finite_positive(1e7));
  c->add_flag("--json", a->json, "print JSON instead of the table");
  c->callback([a] { run_compare(*a); });
}

const ldv::cli::RegisterCommand kRegisterCompareCommand{"compare", &add_compare_command};
}  // namespace
