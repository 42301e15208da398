// ldv: the ldvnav command-line program. Subcommands register themselves (command_registry.hpp).
#include <cstdio>
#include <exception>
#include <map>

#include "common/io/input_error.hpp"
#include "common/logging.hpp"
#include "tools/ldv/cli_checks.hpp"
#include "tools/ldv/command_registry.hpp"

namespace ldv::cli {
namespace {
std::map<std::string, AddCommand>& registry() {
  static std::map<std::string, AddCommand> commands;
  return commands;
}
}  // namespace

RegisterCommand::RegisterCommand(const char* name, AddCommand add) { registry()[name] = add; }

void add_all_commands(CLI::App& app) {
  for (const auto& [name, add] : registry()) add(app);
}
}  // namespace ldv::cli

int main(int argc, char** argv) {
  CLI::App app{"ldv: ldvnav GPS/INS navigation, simulation, calibration and diagnosis tools"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "ldvnav 0.1.0");
  ldv::init_logging();
  ldv::cli::add_all_commands(app);
  ldv::cli::refuse_non_finite_numbers(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const ldv::InputError& e) {
    std::fprintf(stderr, "ldv: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ldv: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
