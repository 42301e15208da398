#pragma once
// What every fuzz target here shares: the input as a file (the readers take paths), and the one way a target
// reports a finding beyond the sanitizers' own (a property the output must have, broken): abort with the reason.
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace ldv::fuzz {

// The readers log what they drop: a log line per input would be most of the fuzzer's time. Silenced once.
inline const bool kQuiet = [] {
  spdlog::set_level(spdlog::level::off);
  return true;
}();

// One file per process (and per role), rewritten for every input.
inline std::string input_file(const uint8_t* data, size_t size, const char* role = "input") {
  const std::string path = "/tmp/ldv_fuzz_" + std::to_string(::getpid()) + "_" + role;
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) std::abort();
  if (size > 0 && std::fwrite(data, 1, size, f) != size) std::abort();
  std::fclose(f);
  return path;
}

// A broken output property: abort, which libFuzzer and the corpus replay both report as a finding.
[[noreturn]] inline void finding(const std::string& what) {
  std::fprintf(stderr, "FUZZ FINDING: %s\n", what.c_str());
  std::fflush(stderr);
  std::abort();
}

inline void require(bool ok, const std::string& what) {
  if (!ok) finding(what);
}

}  // namespace ldv::fuzz
