// Issue 13: what the readers drop reaches `ldv nav`'s summary (counts by reason, a warning beyond 2 %, an
// error with --strict); the configuration's imudatalen is enforced; `ldv compare` matches on the GPS week.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "common/formats/kfgins_files.hpp"
#include "common/geo/earth_model.hpp"
#include "common/io/input_error.hpp"
#include "toolbox/assess/nav_inputs.hpp"
#include "toolbox/assess/solution_comparison.hpp"

namespace ldv::assess {
namespace {
namespace fs = std::filesystem;

std::string input_counts_dir() {
  static const std::string dir = [] {
    const fs::path d = fs::path(::testing::TempDir()) / ("inputcounts_" + std::to_string(::getpid()));
    fs::create_directories(d);
    return d.string() + "/";
  }();
  return dir;
}
std::string write(const std::string& name, const std::string& text) {
  const std::string p = input_counts_dir() + name;
  std::ofstream(p) << text;
  return p;
}
// n IMU rows at 100 Hz; every `bad_every`-th row gets an 8th column (0: none).
std::string imu_rows(int n, int bad_every) {
  std::string s;
  char b[160];
  for (int i = 0; i < n; ++i) {
    std::snprintf(b, sizeof b, "%.6f 0 0 0 0 0 -0.0980665%s\n", 1000.0 + 0.01 * i,
                  bad_every > 0 && i % bad_every == 7 ? " 1" : "");
    s += b;
  }
  return s;
}
std::string gnss_rows(int n) {
  std::string s;
  for (int i = 0; i < n; ++i) {
    s += std::to_string(1000 + i);  // appended apart: gcc 12 warns (-Warray-bounds) on to_string(...) + literal
    s += " 30.5 114.3 20.0 0.01 0.01 0.02\n";
  }
  return s;
}
}  // namespace

TEST(InputCounts, DroppedRecordsAreCountedPerFileAndAboveTwoPercentWarnedOrRefused) {
  NavInputArgs a;
  a.imu = write("imu_5pct.txt", imu_rows(1000, 20));  // 50 of 1000 rows have 8 columns: 5 %
  a.gnss = write("gnss.txt", gnss_rows(10));
  const NavInputs in = load_nav_inputs(a);
  EXPECT_EQ(in.imu.size(), 950u);
  ASSERT_EQ(in.file_counts.size(), 2u);
  EXPECT_EQ(in.file_counts[0].dropped[DropReason::kWrongColumns], 50);
  EXPECT_NEAR(in.file_counts[0].dropped_fraction(), 0.05, 1e-12);
  const auto lines = input_count_lines(in);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_NE(lines[0].find("950 records kept, 50 dropped (5.00 %): 50 wrong column count (first: " + a.imu + ":8:"),
            std::string::npos)
      << lines[0];
  const auto w = input_warnings(in);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("IMU file dropped 5.0 %"), std::string::npos) << w[0];

  a.strict = true;
  try {
    load_nav_inputs(a);
    FAIL() << "--strict accepted a file that dropped 5 %";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("IMU file dropped 5.0 %"), std::string::npos) << e.what();
  }
  a.imu = write("imu_clean.txt", imu_rows(1000, 0));
  EXPECT_TRUE(input_warnings(load_nav_inputs(a)).empty());  // clean input passes --strict
}

TEST(InputCounts, TheConfigurationsImudatalenIsEnforcedAndImuHolesAreWarned) {
  std::string eight;
  for (int i = 0; i < 100; ++i)
    eight += std::to_string(1000.0 + 0.01 * i + (i >= 50 ? 100.0 : 0.0)) + " 0 0 0 0 0 0 5\n";
  const std::string imu = write("imu8.txt", eight), gnss = write("gnss8.txt", gnss_rows(10));
  const std::string yaml = "imupath: " + imu + "\ngnsspath: " + gnss +
                           "\nimudatalen: 8\nimudatarate: 100\nimunoise:\n  arw: [0.2, 0.2, 0.2]\n  vrw: [0.4, 0.4, "
                           "0.4]\n  gbstd: [50, 50, 50]\n  abstd: [250, 250, 250]\n  corrtime: 1.0\n";
  NavInputArgs a;
  a.config = write("cfg8.yaml", yaml);
  const NavInputs in = load_nav_inputs(a);
  EXPECT_EQ(in.imu.size(), 100u);
  ASSERT_EQ(in.imu_gaps.size(), 1u);  // the 100 s hole, exposed for the estimator
  EXPECT_NEAR(in.imu_gaps[0].length_s(), 100.01, 1e-6);
  EXPECT_EQ(in.imu_gaps[0].line, 51);
  const auto w = input_warnings(in);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("IMU has 1 gaps longer than 1 s; the longest 100.010 s"), std::string::npos) << w[0];
  // The same file without the configuration: the KF-GINS 7 columns, every line refused.
  NavInputArgs b;
  b.imu = imu;
  b.gnss = gnss;
  EXPECT_THROW(load_nav_inputs(b), InputError);
}

namespace {
std::vector<NavRecord> records(int week, double sow0, int n, double dt = 1.0) {
  std::vector<NavRecord> v;
  for (int i = 0; i < n; ++i) {
    NavRecord r;
    r.week = week;
    r.sow_s = sow0 + dt * i;
    if (r.sow_s >= 604800.0) {
      r.week += 1;
      r.sow_s -= 604800.0;
    }
    r.pos = earth::offset_ned({0.6, -1.9, 120.0}, Vec3(1.0 * i, 0, 0));  // 1 m/s north
    v.push_back(r);
  }
  return v;
}
}  // namespace

TEST(CompareWeeks, SolutionsAreMatchedOnWeekAndSecondsAcrossARollover) {
  // 100 s crossing the end of week 2379; B is the same trajectory, 0.5 m north.
  const auto a = records(2379, 604750.0, 100);
  auto b = records(2379, 604750.0, 100);
  for (auto& r : b) r.pos = earth::offset_ned(r.pos, Vec3(0.5, 0, 0));
  const ComparisonResult r = compare_solutions(NavSeries::from_records(a), NavSeries::from_records(b), {});
  EXPECT_EQ(r.epochs, 100);
  EXPECT_NEAR(r.stats[1].mean, -0.5, 1e-6);  // north, A minus B
  EXPECT_NEAR(r.stats[1].std, 0.0, 1e-6);
  // Same seconds of week, another week: nothing in common, said plainly (it used to compare them as equal).
  const auto c = records(2400, 604750.0, 100);
  try {
    compare_solutions(NavSeries::from_records(a), NavSeries::from_records(c), {});
    FAIL() << "matched epochs a week apart";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("spans weeks 2379..2380, the second 2400..2401"), std::string::npos)
        << e.what();
  }
}

// Issue 52: a KF-GINS .nav carries seconds of week only (week 0); against a dated truth it used to be refused ("the
// two solutions share no GPS time: the first spans weeks 0..0"). It is matched by seconds of week, and says so.
TEST(CompareWeeks, GivenASolutionWithoutAWeekAndADatedTruth_ThenTheyAreMatchedBySecondsOfWeekAndItIsSaid) {
  auto a = records(2400, 345600.0, 100);
  for (auto& r : a) r.week = 0;
  auto b = records(2400, 345600.0, 100);
  for (auto& r : b) r.pos = earth::offset_ned(r.pos, Vec3(0.5, 0, 0));
  const ComparisonResult r = compare_solutions(NavSeries::from_records(a), NavSeries::from_records(b), {});
  EXPECT_EQ(r.epochs, 100);
  EXPECT_NEAR(r.stats[1].mean, -0.5, 1e-6);
  EXPECT_TRUE(r.matched_by_seconds_of_week);
  EXPECT_NE(comparison_json(r, "a", "b").find("\"matched_by_seconds_of_week\":true"), std::string::npos);
}

}  // namespace ldv::assess

namespace ldv::assess {

TEST(InputCounts, GnssThatDoesNotCoverTheImuIsWarnedAndRefusedWithStrict) {
  // The IMU runs 1000-1010 s; the GNSS file holds another day's fixes (a week-of-seconds mix-up).
  NavInputArgs a;
  a.imu = write("imu_clean.txt", imu_rows(1000, 0));
  std::string far;
  for (int i = 0; i < 10; ++i) far += std::to_string(90000 + i) + " 30.5 114.3 20.0 0.01 0.01 0.02\n";
  a.gnss = write("gnss_other_day.txt", far);
  const NavInputs in = load_nav_inputs(a);
  const auto w = input_warnings(in);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("0 of 10 GNSS fixes"), std::string::npos) << w[0];
  a.strict = true;
  EXPECT_THROW(load_nav_inputs(a), InputError);
  a.gnss = write("gnss_same_time.txt", gnss_rows(10));
  a.strict = false;
  EXPECT_TRUE(input_warnings(load_nav_inputs(a)).empty());
}

}  // namespace ldv::assess
