#pragma once
// Test helpers: what `ldv ARGS` prints (stdout and stderr together), the built program run as a user runs it.
#include <cstdio>
#include <string>

namespace ldv::est::test {

// What a shell command prints, stdout and stderr together (the test's own commands, e.g. gpsbabel).
inline std::string command_output(const std::string& command) {
  std::string text;
  if (FILE* p = ::popen((command + " 2>&1").c_str(), "r")) {
    char buf[4096];
    while (size_t n = std::fread(buf, 1, sizeof buf, p)) text.append(buf, n);
    ::pclose(p);
  }
  return text;
}

inline std::string ldv_output(const std::string& args) {
  return command_output(std::string(LDV_BIN_DIR) + "/ldv " + args);
}

}  // namespace ldv::est::test
