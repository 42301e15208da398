// odo.txt (common/formats/odometer_text.hpp): what the writer writes reads back; malformed input is refused
// with file:line and what was expected.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "common/formats/odometer_text.hpp"
#include "common/io/input_error.hpp"

using namespace ldv;
namespace fs = std::filesystem;

namespace {
std::string file_with(const std::string& name, const std::string& text) {
  const fs::path p = fs::temp_directory_path() / ("ldv_formats_test_" + name);
  std::ofstream(p) << text;
  return p.string();
}
std::string error_reading(const std::string& path) {
  try {
    read_odometer_text(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(FormatsOdometerText, WrittenSamplesReadBack) {
  const std::vector<OdometerSample> s = {{345600.0, 0.0}, {345600.02, -1.234567}, {345600.04, 25.000001}};
  const std::string p = (fs::temp_directory_path() / "ldv_formats_test_odo_roundtrip.txt").string();
  write_odometer_text(p, s);
  const auto back = read_odometer_text(p);
  ASSERT_EQ(back.size(), 3u);
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(back[i].t_s, s[i].t_s, 1e-9);
    EXPECT_NEAR(back[i].speed_mps, s[i].speed_mps, 1e-9);
  }
}

TEST(FormatsOdometerText, CommentsBlankLinesCommasAndCrlfAreAccepted) {
  const auto s =
      read_odometer_text(file_with("odo_ok.txt", "# sow speed\r\n\r\n100.0 1.5\r\n% rtklib style\n100.5,2.5\n"));
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[1].t_s, 100.5);
  EXPECT_EQ(s[1].speed_mps, 2.5);
}

TEST(FormatsOdometerText, MalformedInputNamesFileLineAndExpectation) {
  struct Case {
    std::string text, message;
  };
  const std::vector<Case> cases = {
      {"100 1\n101 2 3\n", ":2: expected 2 columns 'sow speed_mps', found 3"},
      {"100\n", ":1: expected 2 columns 'sow speed_mps', found 1"},
      {"100 1\n101 fast\n", ":2: expected 'sow speed_mps' (2 numbers): column 2: expected a number, found 'fast'"},
      {"100 nan\n", ":1: expected 'sow speed_mps' (2 numbers): column 2: expected a finite number, found 'nan'"},
      {"100 1\n100 2\n",
       ":2: column 1 (sow): expected a time after the previous line's 100.000000 s, found 100.000000 s"},
      {"100 1\n99 2\n", ":2: column 1 (sow): expected a time after the previous line's"},
      {"604800 1\n", ":1: column 1 (sow): expected GPS seconds of week in [0, 604800)"},
      {"-1 1\n", ":1: column 1 (sow): expected GPS seconds of week in [0, 604800)"},
      {"# nothing\n", ": expected odometer samples 'sow speed_mps', found none"},
  };
  int i = 0;
  for (const Case& c : cases) {
    const std::string p = file_with("odo_bad_" + std::to_string(i++) + ".txt", c.text);
    const std::string e = error_reading(p);
    EXPECT_EQ(e.rfind(p, 0), 0u) << e;  // starts with the file name
    EXPECT_NE(e.find(c.message), std::string::npos) << "got: " << e << "\nexpected: " << c.message;
  }
  EXPECT_NE(error_reading("/nonexistent/odo.txt"), "");
  EXPECT_NE(error_reading("/dev/zero"), "");  // not a regular file: refused, not read forever
}

TEST(FormatsOdometerText, NonFiniteSamplesAreNotWritten) {
  const std::string p = (fs::temp_directory_path() / "ldv_formats_test_odo_nan.txt").string();
  EXPECT_THROW(write_odometer_text(p, {{1.0, 0.0}, {2.0, std::nan("")}}), InputError);
}
