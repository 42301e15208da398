#pragma once
// Runs a program with an argument vector, never through a shell (a path or a label from the user's data cannot
// become a command): fork, chdir, exec; standard input from /dev/null, standard output and error to the files given
// (relative to work_dir when relative; "/dev/null" discards; one that cannot be opened leaves the stream inherited).
// Waits for it.
#include <filesystem>
#include <string>
#include <vector>

namespace ldv {

// The program's exit status: 0 = success; -1 = it could not be started or did not exit normally; 126 the working
// folder could not be entered, 127 the program could not be run.
int run_program(const std::vector<std::string>& argv, const std::filesystem::path& work_dir,
                const std::filesystem::path& stdout_path, const std::filesystem::path& stderr_path);

}  // namespace ldv
