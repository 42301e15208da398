#pragma once
// Each tools/ldv/cmd_<name>.cpp adds its subcommand to the `ldv` program by defining one static
//   static const ldv::cli::RegisterCommand kRegister{"sim", &add_sim_command};
// so adding a subcommand never edits main.cpp.
#include <CLI/CLI.hpp>
#include <functional>
#include <string>

namespace ldv::cli {

using AddCommand = void (*)(CLI::App& ldv_app);

struct RegisterCommand {
  RegisterCommand(const char* name, AddCommand add);
};

void add_all_commands(CLI::App& app);

}  // namespace ldv::cli
