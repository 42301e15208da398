#pragma once
// Runs `ldv` with arguments, no shell between: a hostile argument stays one argument. Output goes to a
// file the test can read; a time limit turns a hang into a failure instead of a stuck suite.
#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace ldv::test {

struct CliResult {
  int exit_code = -1;  // -1: killed by a signal or the time limit
  int signal = 0;      // the signal that ended it, 0 if it exited
  bool timed_out = false;
  std::string output;  // stdout and stderr together
};

inline CliResult run_ldv(const std::vector<std::string>& args, double time_limit_s = 60.0,
                         long memory_limit_bytes = 4L << 30) {
  namespace fs = std::filesystem;
  static int serial = 0;
  const fs::path out =
      fs::temp_directory_path() / ("ldv_cli_" + std::to_string(getpid()) + "_" + std::to_string(serial++) + ".log");
  std::vector<std::string> argv_s{std::string(LDV_BIN_DIR) + "/ldv"};
  argv_s.insert(argv_s.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_s) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    const int fd = open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, STDOUT_FILENO);
    dup2(fd, STDERR_FILENO);
#ifndef __SANITIZE_ADDRESS__  // ASan reserves terabytes of shadow address space: no RLIMIT_AS under it
    const rlimit mem{static_cast<rlim_t>(memory_limit_bytes), static_cast<rlim_t>(memory_limit_bytes)};
    setrlimit(RLIMIT_AS, &mem);  // unbounded allocation becomes a failure we can see
#else
    (void)memory_limit_bytes;
#endif
    execv(argv[0], argv.data());
    _exit(127);
  }
  CliResult r;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(time_limit_s);
  int status = 0;
  for (;;) {
    const pid_t w = waitpid(pid, &status, WNOHANG);
    if (w == pid) break;
    if (std::chrono::steady_clock::now() > deadline) {
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      r.timed_out = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (!r.timed_out && WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
  if (!r.timed_out && WIFSIGNALED(status)) r.signal = WTERMSIG(status);
  std::ifstream f(out);
  std::stringstream s;
  s << f.rdbuf();
  r.output = s.str();
  fs::remove(out);
  return r;
}

// A clear refusal: exit code 1 or 2 (CLI11 uses 105-ish codes for parse errors; any non-zero exit that is
// not a crash counts), no signal, no hang, and a message that says what was wrong.
inline bool is_clear_error(const CliResult& r) {
  return !r.timed_out && r.signal == 0 && r.exit_code > 0 && r.exit_code != 127 && !r.output.empty();
}

}  // namespace ldv::test
