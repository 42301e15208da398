#include "common/io/run_program.hpp"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>

namespace ldv {

int run_program(const std::vector<std::string>& argv, const std::filesystem::path& work_dir,
                const std::filesystem::path& stdout_path, const std::filesystem::path& stderr_path) {
  if (argv.empty()) return -1;
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  const pid_t pid = fork();
  if (pid < 0) return -1;
  if (pid == 0) {  // child: only async-signal-safe calls until exec
    if (chdir(work_dir.c_str()) != 0) _exit(126);
    const int null_fd = open("/dev/null", O_RDWR | O_CLOEXEC);
    const int out_fd = open(stdout_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    // The same file for both: one descriptor, so the two streams interleave instead of overwriting each other.
    const int err_fd =
        stderr_path == stdout_path ? out_fd : open(stderr_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (null_fd >= 0) dup2(null_fd, STDIN_FILENO);
    if (out_fd >= 0) dup2(out_fd, STDOUT_FILENO);  // a file that cannot be opened leaves the stream as inherited
    if (err_fd >= 0) dup2(err_fd, STDERR_FILENO);
    execvp(args[0], args.data());
    _exit(127);
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return -1;
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace ldv
