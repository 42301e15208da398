// Issue 46 (6): numbers a user gives on the command line are checked where they are given. `--week 99999999`,
// `calib static --height-m 1e9` and `--gravity 0` reached the work unchecked; each numeric option now carries
// bounds, or is checked by the library that uses it (ldv sim's request), and both kinds are tested here.
#include <gtest/gtest.h>

#include <sstream>
#include <utility>

#include "cli_run.hpp"

namespace ldv::test {
namespace {

TEST(CliNumbers, EveryOptionThatTakesANumberHasBounds) {
  // given every option of every command; when listing those with a number and no bounds
  const CliResult r = run_ldv({"help", "--unbounded-numbers"});
  // then there are none
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output, "");
}

TEST(CliNumbers, OptionsTheLibraryChecksRefuseHugeAndNegativeValuesByName) {
  // given the options whose numbers the library checks where it uses them
  const CliResult list = run_ldv({"help", "--checked-where-used"});
  ASSERT_EQ(list.exit_code, 0) << list.output;
  std::istringstream lines(list.output);
  std::string ldv_word, command, option;
  int values = 0, checked = 0;
  while (lines >> ldv_word >> command >> option >> values) {
    for (const char* huge : {"1e12", "-1e12"}) {
      std::string value = huge;
      for (int i = 1; i < values; ++i) value += std::string(",") + huge;
      // when each is given a value no sensor, vehicle or clock has
      const CliResult r = run_ldv({command, option, value, "--out", "/nonexistent-dir-never-written/x"}, 60.0);
      // then the command refuses it (input or usage error) naming the option, and writes nothing
      EXPECT_TRUE(r.exit_code == 2 || r.exit_code == 64) << option << " " << value << ": " << r.output;
      EXPECT_NE(r.output.find(option), std::string::npos) << option << " " << value << ": " << r.output;
    }
    ++checked;
  }
  EXPECT_GE(checked, 10) << list.output;  // ldv sim's vehicle and clock options at least
}

TEST(CliNumbers, TheIssuesExamplesAreRefusedNamingTheOption) {
  // given the values the third hostile campaign gave; when run; then each is refused before any work
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
      {"--week", {"nav", "--kfgins-config", "/nonexistent.yaml", "--week", "99999999"}},
      {"--week", {"nav", "--kfgins-config", "/nonexistent.yaml", "--week", "-5"}},
      {"--week", {"play", "--week", "99999999"}},
      {"--height-m", {"calib", "static", "/nonexistent.csv", "--height-m", "1e9"}},
      {"--lat-deg", {"calib", "static", "/nonexistent.csv", "--lat-deg", "91"}},
      {"--gravity", {"calib", "static", "/nonexistent.csv", "--gravity", "0"}},
      {"lever_arm", {"sim", "--effect", "lever_arm=1e9,0,0", "--out", "/nonexistent-dir-never-written/x"}},
  };
  for (const auto& [named, args] : cases) {
    const CliResult r = run_ldv(args);
    EXPECT_TRUE(r.exit_code == 2 || r.exit_code == 64) << args[0] << " " << named << ": " << r.output;
    EXPECT_NE(r.output.find(named), std::string::npos) << r.output;
  }
}

}  // namespace
}  // namespace ldv::test
