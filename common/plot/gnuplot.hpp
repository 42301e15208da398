#pragma once
// The one way ldvnav talks to gnuplot. Text from users' data (CSV column names, JSON units, labels,
// model names, file names) reaches gnuplot scripts, so it must never be able to run a command:
// - every string goes into the script as a complete single-quoted literal (gnuplot expands neither
//   backquotes nor @macros inside single quotes; a quote is doubled; a line break, which would end the
//   literal and start a new command, becomes a space);
// - gnuplot itself is started by fork/exec with the script as an argument, never through a shell.
#include <filesystem>
#include <string>
#include <string_view>

namespace ldv::plot {

// Displayed text (titles, labels, key entries) for a terminal in enhanced mode: '_', '^', '{', '}', '@',
// '&', '~' are escaped so that they print as themselves.
std::string gnuplot_label(std::string_view text);

// Text for a terminal set `noenhanced`, and file names: only quoting and control characters handled.
std::string gnuplot_literal(std::string_view text);

// Runs `gnuplot script` with `work_dir` as the working directory; its stderr goes to `log_path`
// (relative to work_dir when relative). Returns the exit status (0 = success, -1 = could not start).
int run_gnuplot(const std::filesystem::path& script, const std::filesystem::path& work_dir,
                const std::filesystem::path& log_path = "/dev/null");

}  // namespace ldv::plot
