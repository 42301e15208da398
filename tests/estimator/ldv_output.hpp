#pragma once
// Test helper: what `ldv ARGS` prints (stdout and stderr together), the built program run as a user runs it.
#include <cstdio>
#include <string>

namespace ldv::est::test {

inline std::string ldv_output(const std::string& args) {
  std::string text;
  if (FILE* p = ::popen((std::string(LDV_BIN_DIR) + "/ldv " + args + " 2>&1").c_str(), "r")) {
    char buf[4096];
    while (size_t n = std::fread(buf, 1, sizeof buf, p)) text.append(buf, n);
    ::pclose(p);
  }
  return text;
}

}  // namespace ldv::est::test
