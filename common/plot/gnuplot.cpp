#include "common/plot/gnuplot.hpp"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>

namespace ldv::plot {
namespace {

std::string quoted(std::string_view text, bool enhanced) {
  std::string o = "'";
  for (const char c : text) {
    const unsigned char u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f) {  // line breaks, NUL and other controls: never part of a literal
      o += ' ';
      continue;
    }
    if (c == '\'') {
      o += "''";
      continue;
    }
    if (enhanced && (c == '_' || c == '^' || c == '{' || c == '}' || c == '@' || c == '&' || c == '~' || c == '\\'))
      o += '\\';
    o += c;
  }
  return o + "'";
}

}  // namespace

std::string gnuplot_label(std::string_view text) { return quoted(text, true); }
std::string gnuplot_literal(std::string_view text) { return quoted(text, false); }

int run_gnuplot(const std::filesystem::path& script, const std::filesystem::path& work_dir,
                const std::filesystem::path& log_path) {
  // A relative name starting with '-' would read as an option.
  const std::string script_arg = script.is_absolute() ? script.string() : "./" + script.string();
  const pid_t pid = fork();
  if (pid < 0) return -1;
  if (pid == 0) {  // child: only async-signal-safe calls until exec
    if (chdir(work_dir.c_str()) != 0) _exit(126);
    const int log_fd = open(log_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    const int null_fd = open("/dev/null", O_RDWR | O_CLOEXEC);
    if (log_fd >= 0) dup2(log_fd, STDERR_FILENO);
    if (null_fd >= 0) {
      dup2(null_fd, STDIN_FILENO);
      dup2(null_fd, STDOUT_FILENO);
    }
    const char* argv[] = {"gnuplot", script_arg.c_str(), nullptr};
    execvp("gnuplot", const_cast<char* const*>(argv));
    _exit(127);
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return -1;
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace ldv::plot
