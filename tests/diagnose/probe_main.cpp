// Development probe (not a test): diagnose one simulated case and print the report.
//   probe_diagnose GRADE EFFECT|none SEED DURATION MODEL
#include <iostream>

#include "tests/diagnose/sim_case.hpp"
#include "toolbox/diagnose/report_text.hpp"
#include "toolbox/diagnose/report_json.hpp"

int main(int argc, char** argv) {
  using namespace ldv::diag::testing;
  SimCase c;
  if (argc > 1) c.grade = argv[1];
  if (argc > 2 && std::string(argv[2]) != "none") c.effect = argv[2];
  if (argc > 3) c.seed = std::stoul(argv[3]);
  if (argc > 4) c.duration_s = std::stod(argv[4]);
  const std::string model = argc > 5 ? argv[5] : "kfgins21";
  if (argc > 6) c.gnss_rate_hz = std::stod(argv[6]);
  const auto r = simulate(c);
  auto opt = options(r, model);
  opt.verbose = true;
  const auto d = ldv::diag::diagnose(inputs(r), opt);
  ldv::diag::print_report(std::cout, d);
  if (argc > 7) ldv::diag::write_json(d, argv[7]);
  return 0;
}
