// The default suite's run of a fuzz target (gcc build, no libFuzzer): every file of the given corpus folders
// through LLVMFuzzerTestOneInput once. The kept corpus is then a regression test of its own: an input that once
// crashed a reader, or a seed, must keep passing. The coverage-guided search itself is the `fuzz` label's
// (tests/fuzz/run_libfuzzer.sh, clang's libFuzzer with ASan + UBSan).
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

int main(int argc, char** argv) {
  namespace fs = std::filesystem;
  long inputs = 0;
  for (int a = 1; a < argc; ++a) {
    if (!fs::is_directory(argv[a])) {
      std::fprintf(stderr, "corpus folder %s missing\n", argv[a]);
      return 2;
    }
    for (const auto& entry : fs::directory_iterator(argv[a])) {
      if (!entry.is_regular_file()) continue;
      std::ifstream in(entry.path(), std::ios::binary);
      const std::vector<uint8_t> bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
      LLVMFuzzerTestOneInput(bytes.data(), bytes.size());
      ++inputs;
    }
  }
  std::printf("%ld corpus inputs replayed without a finding\n", inputs);
  return inputs > 0 ? 0 : 2;
}
