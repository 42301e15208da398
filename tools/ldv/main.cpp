// ldv: the ldvnav command-line program. Subcommands register themselves (command_registry.hpp).
#include <cstdio>
#include <exception>
#include <map>
#include <string>

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

// Exit codes, the same for every command (README, "The `ldv` tool"): 0 done; 1 the work failed (a file could not be
// written, a bus or device error, an internal error); 2 the input was refused (a file, line, key or option value,
// named in the message); 64 the command line itself (an unknown command or option, a missing argument: EX_USAGE).
constexpr int kExitFailed = 1, kExitInputRefused = 2, kExitUsage = 64;

int main(int argc, char** argv) {
  CLI::App app{"ldv: ldvnav GPS/INS navigation, simulation, calibration and diagnosis tools"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "ldvnav 0.1.0");
  app.footer(
      "`ldv help COMMAND` or `ldv COMMAND --help`: a command's options. Exit codes: 0 done, 1 the work failed, "
      "2 the input was refused, 64 the command line is wrong.");
  ldv::init_logging();
  ldv::cli::add_all_commands(app);
  ldv::cli::refuse_non_finite_numbers(app);
  // `ldv help [COMMAND]`: what `--help` prints (a user's first try; it said "A subcommand is required").
  if (argc == 3 && std::string(argv[1]) == "help" && std::string(argv[2]) == "--unbounded-numbers") {
    const auto unbounded = ldv::cli::unbounded_number_options(app);
    for (const auto& name : unbounded) std::printf("%s\n", name.c_str());
    return unbounded.empty() ? 0 : kExitFailed;
  }
  if (argc == 3 && std::string(argv[1]) == "help" && std::string(argv[2]) == "--checked-where-used") {
    for (const auto& name : ldv::cli::checked_where_used_options(app)) std::printf("%s\n", name.c_str());
    return 0;
  }
  if (argc >= 2 && std::string(argv[1]) == "help") {
    if (argc == 2) {
      std::fputs(app.help().c_str(), stdout);
      return 0;
    }
    for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
      if (sub->get_name() == argv[2]) {
        std::fputs(sub->help().c_str(), stdout);
        return 0;
      }
    std::fprintf(stderr, "ldv: no command '%s' (`ldv help` lists them)\n", argv[2]);
    return kExitUsage;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);  // prints the help, the version or the error
    return code == 0 ? 0 : kExitUsage;
  } catch (const ldv::InputError& e) {
    std::fprintf(stderr, "ldv: error: %s\n", e.what());
    return kExitInputRefused;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ldv: error: %s\n", e.what());
    return kExitFailed;
  }
  return 0;
}
