// RTKLIB .pos input of ldv nav / outage / diagnose (toolbox/assess/nav_inputs.cpp): records in GPS time
// order across a week rollover and after a record stamped ahead; non-positive sigmas refused as malformed.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "common/io/input_error.hpp"
#include "toolbox/assess/nav_inputs.hpp"

namespace ldv::assess {
namespace {

std::string temp_path(const std::string& name) {
  const auto dir = std::filesystem::path(::testing::TempDir()) / ("navpos_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

// Two KF-GINS IMU samples: the reader needs an IMU file, its content does not matter here.
std::string imu_file() {
  const std::string path = temp_path("imu.txt");
  std::ofstream(path) << "100.000 0 0 0 0 0 0\n100.010 0 0 0 0 0 0\n";
  return path;
}

// One .pos line, week/tow layout, RTK fixed, sigmas (sdn, sde, sdu).
std::string pos_line(int week, double tow_s, double sd_m = 0.01) {
  char b[200];
  std::snprintf(b, sizeof b, "%d %.3f 35.100000000 136.900000000 104.8000 1 10 %.4f %.4f %.4f 0 0 0 0.0 9.9\n", week,
                tow_s, sd_m, sd_m, 2 * sd_m);
  return b;
}

NavInputs load(const std::string& pos_text) {
  const std::string pos = temp_path("gnss.pos");
  std::ofstream(pos) << "%  GPST   latitude(deg) longitude(deg)  height(m)   Q  ns   sdn(m)\n" << pos_text;
  NavInputArgs a;
  a.imu = imu_file();
  a.rtklib_pos = pos;
  return load_nav_inputs(a);
}

}  // namespace

TEST(NavInputsPos, GivenAWeekRollover_ThenEveryFixIsKeptOnContinuousTime) {
  const NavInputs in =
      load(pos_line(2300, 604798.0) + pos_line(2300, 604799.0) + pos_line(2301, 0.0) + pos_line(2301, 1.0));
  ASSERT_EQ(in.gnss.size(), 4u);
  EXPECT_EQ(in.gps_week, 2300);
  EXPECT_DOUBLE_EQ(in.gnss[2].t_s, 604800.0);  // week 2301 sow 0 = 604800 s after the start of week 2300
  EXPECT_DOUBLE_EQ(in.gnss[3].t_s, 604801.0);
}

TEST(NavInputsPos, GivenOneRecordStampedAhead_ThenTheLaterFixesAreNotDroppedAsRepeated) {
  std::string text;
  for (int k = 0; k < 5; ++k) text += pos_line(2300, 100.0 + k);
  text += pos_line(2300, 5000.0);  // one forward jump: the record after it is the one out of file order
  for (int k = 5; k < 10; ++k) text += pos_line(2300, 100.0 + k);
  text += pos_line(2300, 109.0);  // a true repeat of the epoch before
  const NavInputs in = load(text);
  ASSERT_EQ(in.gnss.size(), 11u);  // 10 epochs 100..109 and the one at 5000, each once
  for (int k = 0; k < 10; ++k) EXPECT_DOUBLE_EQ(in.gnss[k].t_s, 100.0 + k);
  EXPECT_DOUBLE_EQ(in.gnss[10].t_s, 5000.0);
  EXPECT_NE(in.gnss_note.find("1 repeated"), std::string::npos) << in.gnss_note;
  EXPECT_NE(in.gnss_note.find("1 out of file order"), std::string::npos) << in.gnss_note;
}

TEST(NavInputsPos, GivenNonPositiveSigmas_ThenThoseRecordsAreMalformedAndCountedByReason) {
  std::string text = pos_line(2300, 100.0) + pos_line(2300, 101.0, 0.0) + pos_line(2300, 102.0, -0.01);
  for (int k = 3; k < 30; ++k) text += pos_line(2300, 100.0 + k);  // 2 of 30 malformed: under the 10 % rule
  const NavInputs in = load(text);
  ASSERT_EQ(in.gnss.size(), 28u);
  EXPECT_DOUBLE_EQ(in.gnss[1].t_s, 103.0);
  // The first such line is named (line 3: the header is line 1).
  EXPECT_NE(in.gnss_note.find("2 malformed (position sigma not positive, first at line 3)"), std::string::npos)
      << in.gnss_note;
}

TEST(NavInputsPos, GivenOnlyZeroSigmas_ThenLoadingFailsNamingTheLineInsteadOfRejectingEveryFixLater) {
  std::string text;
  for (int k = 0; k < 120; ++k) text += pos_line(2300, 100.0 + k, 0.0);
  try {
    load(text);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 2);  // the first record, after the header line
    EXPECT_NE(std::string(e.what()).find("120 malformed (position sigma not positive"), std::string::npos) << e.what();
  }
}

// Issue 35, item 15: one record dated 1980/01/06, or with a week of 99999999999 (an int overflow) or a year of
// 2147483647, moved the reference week: 0 of 121 fixes used, a free-inertial run with exit 0.
TEST(NavInputsPos, GivenOneRecordOfAnImpossibleDate_ThenItIsMalformedAndEveryOtherFixKeepsItsTime) {
  for (const std::string& bad :
       {std::string("1980/01/06 00:00:00.000 35.1 136.9 104.8 1 10 0.01 0.01 0.02 0 0 0 0.0 9.9\n"),
        std::string("99999999999 100.000 35.1 136.9 104.8 1 10 0.01 0.01 0.02 0 0 0 0.0 9.9\n"),
        std::string("2147483647/01/06 00:00:00.000 35.1 136.9 104.8 1 10 0.01 0.01 0.02 0 0 0 0.0 9.9\n"),
        std::string("0 100.000 35.1 136.9 104.8 1 10 0.01 0.01 0.02 0 0 0 0.0 9.9\n")}) {
    std::string text;
    for (int k = 0; k < 121; ++k) text += k == 60 ? bad : pos_line(2300, 100.0 + k);
    const NavInputs in = load(text);
    EXPECT_EQ(in.gps_week, 2300) << bad;
    ASSERT_EQ(in.gnss.size(), 120u) << bad;
    EXPECT_DOUBLE_EQ(in.gnss.front().t_s, 100.0);
    EXPECT_DOUBLE_EQ(in.gnss.back().t_s, 220.0);
    EXPECT_NE(in.gnss_note.find("1 malformed"), std::string::npos) << in.gnss_note;
  }
}

// Issue 35, item 16: 200 malformed lines and 1 good one were read with exit 0 and no line numbers.
TEST(NavInputsPos, GivenMostLinesMalformed_ThenTheFileIsRefusedNamingTheFirstBadLine) {
  std::string text = pos_line(2300, 100.0);
  for (int k = 0; k < 200; ++k) text += "2300 10x.000 35.1 136.9 104.8 1 10 0.01 0.01 0.02 0 0 0 0.0 9.9\n";
  try {
    load(text);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 3);
    EXPECT_NE(std::string(e.what()).find("200 of 201 solution lines malformed"), std::string::npos) << e.what();
  }
}

}  // namespace ldv::assess
