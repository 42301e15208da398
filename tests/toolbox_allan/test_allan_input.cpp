// Inputs: the same sensor in deg/s, rad/s or counts gives the same SI result; KF-GINS increments
// become rates; bad input gives a message naming file, line and column, never NaN output.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>

#include "common/io/input_error.hpp"
#include "tests/toolbox_allan/sensor_sim.hpp"
#include "toolbox/allan/allan_input.hpp"
#include "toolbox/allan/analysis.hpp"

using namespace ldv::allan;
using namespace ldv::allan::test;
namespace fs = std::filesystem;

namespace {

std::string temp_path(const std::string& name) { return (fs::temp_directory_path() / ("ldv_allan_" + name)).string(); }

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const ldv::InputError& e) {
    return e.what();
  }
  return "";
}

double fitted_n(const std::vector<PhaseSeries>& ch) {
  AnalysisOptions opt;
  return (*analyze(ch, opt).front().fit)[ModelTerm::kN].value;
}

}  // namespace

TEST(AllanInput, SameSensorInDegRadAndCountsGivesSameSi) {
  SensorTruth t;
  t.n = 2e-4;       // rad/s/sqrt(Hz)
  t.bias = 0.01;    // rad/s
  const double dt = 0.01;
  const auto y = simulate_rate(t, dt, 50000, 11);
  const double kDeg = M_PI / 180.0, counts_per_dps = 131.0;
  const std::string path = temp_path("units.csv");
  {
    std::ofstream f(path);
    f.precision(17);
    f << "t,rate_rad,rate_deg,rate_counts\n";
    for (size_t i = 0; i < y.size(); ++i) {
      f << i * dt << ',' << y[i] << ',' << y[i] / kDeg << ',' << y[i] / kDeg * counts_per_dps << '\n';
    }
  }
  InputOptions opt;
  opt.format = InputFormat::kCsv;
  opt.time_column = "t";
  opt.columns = {"rate_rad"};
  opt.units = {"rad/s"};
  const double n_rad = fitted_n(read_allan_input(path, opt));
  opt.columns = {"rate_deg"};
  opt.units = {"deg/s"};
  const double n_deg = fitted_n(read_allan_input(path, opt));
  opt.columns = {"4"};  // by index
  opt.counts_per_unit = {counts_per_dps};
  const auto counts = read_allan_input(path, opt);
  EXPECT_EQ(counts.front().unit, "rad/s");
  EXPECT_NEAR(counts.front().tau0_s, dt, 1e-12);
  const double n_counts = fitted_n(counts);
  EXPECT_NEAR(n_deg / n_rad, 1.0, 1e-9);
  EXPECT_NEAR(n_counts / n_rad, 1.0, 1e-9);
  EXPECT_NEAR(n_rad / t.n, 1.0, 0.03);
}

TEST(AllanInput, KfGinsIncrementsBecomeRates) {
  const std::string path = temp_path("imu.txt");
  {
    std::ofstream f(path);
    f.precision(17);
    for (int i = 1; i <= 2000; ++i) {
      const double d = 0.005 * (1 + 0.1 * std::sin(i * 1.3));  // varying increments
      f << 100.0 + i * 0.005 << ' ' << 1e-5 * d << ' ' << 2e-5 * d << ' ' << 3e-5 * d << ' ' << d << ' ' << 2 * d << ' '
        << 9.8 * 0.005 + d << '\n';
    }
  }
  InputOptions opt;
  opt.format = InputFormat::kKfGins;
  const auto ch = read_allan_input(path, opt);
  ASSERT_EQ(ch.size(), 6u);
  EXPECT_EQ(ch[0].name, "gyro_x");
  EXPECT_EQ(ch[5].name, "accel_z");
  EXPECT_EQ(ch[0].unit, "rad/s");
  EXPECT_EQ(ch[3].unit, "m/s^2");
  EXPECT_NEAR(ch[0].tau0_s, 0.005, 1e-12);
  EXPECT_NEAR(ch[5].mean_rate, 9.8 + 1.0, 0.01);  // increment / interval
}

TEST(AllanInput, BadInputNamesFileLineAndColumn) {
  InputOptions csv;
  csv.format = InputFormat::kCsv;
  csv.rate_hz = 100;
  const std::string empty = temp_path("empty.csv");
  std::ofstream(empty).close();
  EXPECT_NE(error_of([&] { read_allan_input(empty, csv); }).find("empty file"), std::string::npos);

  const std::string nan = temp_path("nan.csv");
  std::ofstream(nan) << "a,b\n1,2\n3,nan\n";
  const std::string e_nan = error_of([&] { read_allan_input(nan, csv); });
  EXPECT_NE(e_nan.find(nan + ":3"), std::string::npos) << e_nan;
  EXPECT_NE(e_nan.find("column 2"), std::string::npos) << e_nan;

  const std::string constant = temp_path("constant.csv");
  {
    std::ofstream f(constant);
    f << "a\n";
    for (int i = 0; i < 100; ++i) f << "1.5\n";
  }
  EXPECT_NE(error_of([&] { read_allan_input(constant, csv); }).find("constant"), std::string::npos);

  const std::string short_file = temp_path("short.csv");
  std::ofstream(short_file) << "a\n1\n2\n3\n";
  EXPECT_NE(error_of([&] { read_allan_input(short_file, csv); }).find("at least 8"), std::string::npos);

  InputOptions units = csv;
  units.units = {"furlongs/fortnight"};
  const std::string e_unit = error_of([&] { read_allan_input(nan, units); });
  EXPECT_NE(e_unit.find("unknown unit 'furlongs/fortnight'"), std::string::npos) << e_unit;

  InputOptions column = csv;
  column.columns = {"gyro"};
  EXPECT_NE(error_of([&] { read_allan_input(nan, column); }).find("no column 'gyro'"), std::string::npos);

  const std::string ragged = temp_path("ragged.csv");
  std::ofstream(ragged) << "a,b\n1,2\n3\n";
  EXPECT_NE(error_of([&] { read_allan_input(ragged, csv); }).find(ragged + ":3"), std::string::npos);

  InputOptions phase;
  phase.format = InputFormat::kPhase;
  const std::string words = temp_path("words.dat");
  std::ofstream(words) << "header one\nheader two\nheader three\n1\n2\n";
  EXPECT_NE(error_of([&] { read_allan_input(words, phase); }).find(words + ":3"), std::string::npos);
}

TEST(AllanInput, TauBeyondTheDataIsAClearError) {
  SensorTruth t;
  t.n = 1e-3;
  AnalysisOptions opt;
  opt.taus_s = {1.0, 600.0};  // OADEV allows m <= 500 with 1001 phase points
  const PhaseSeries s = phase_from_rates(simulate_rate(t, 1.0, 1000, 1), 1.0, "x", "rad/s");
  try {
    analyze({s}, opt);
    FAIL() << "expected an error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("too short"), std::string::npos) << e.what();
  }
}

TEST(AllanCli, PhaseDatToJson) {
  const std::string json = temp_path("phase.json");
  const std::string cmd = std::string(LDV_BIN_DIR) + "/ldv allan " + LDV_SHARED_DATA_DIR +
                          "/allan/phasedat/PHASE.DAT --format phase --tau0 1 --taus octave --json " + json +
                          " > /dev/null 2>&1";
  if (!fs::exists(std::string(LDV_BIN_DIR) + "/ldv")) GTEST_SKIP() << "ldv not built";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  std::ifstream f(json);
  const std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  for (const char* key : {"\"name\": \"phase\"", "\"taus_s\": [1,2,4,8,16,32,64,128]", "\"oadev\": [0.2922", "\"oadev_lo\"",
                          "\"oadev_hi\"", "\"N\":", "\"N_sigma\":", "\"B_tau_s\":", "\"K_resolved\":", "\"R\":"}) {
    EXPECT_NE(text.find(key), std::string::npos) << key;
  }
  // Non-finite numbers would be written as null: there must be none (and no raw nan/inf).
  EXPECT_EQ(text.find("null"), std::string::npos);
  EXPECT_EQ(text.find("nan"), std::string::npos);
  EXPECT_EQ(text.find(": inf"), std::string::npos);
}

// Issue 46 (6), silent drops: ldv allan took the median interval of the stamps, so a 100 Hz record whose stamps
// jitter between 6 and 14 ms was analysed as 167 Hz, and holes went unsaid. The mean of the regular intervals is
// the interval; holes hiding more than 1 % of the record are refused naming the line after the first; fewer are
// said and bridged.
TEST(AllanInput, GivenJitteredStampsOrHoles_ThenTheIntervalIsTheMeanAndHolesAreNamed) {
  const auto write = [](const std::string& name, const std::function<double(int)>& t_of) {
    const std::string path = temp_path(name);
    std::ofstream f(path);
    f.precision(17);
    for (int i = 0; i < 4000; ++i)
      f << t_of(i) << ' ' << 1e-6 * std::sin(i * 0.7) << ' ' << 1e-6 * std::sin(i * 1.1) << ' '
        << 1e-6 * std::sin(i * 1.7) << ' ' << 1e-4 * std::cos(i * 0.3) << ' ' << 1e-4 * std::cos(i * 0.9) << ' '
        << 0.098 + 1e-4 * std::cos(i * 1.3) << '\n';
    return path;
  };
  InputOptions opt;
  opt.format = InputFormat::kKfGins;
  // stamps of a 100 Hz unit read late by 0 or 4 ms in turn: intervals 6 and 14 ms
  const std::string jitter = write("jitter.txt", [](int i) { return 100.0 + 0.01 * i + (i % 2 ? 0.004 : 0.0); });
  EXPECT_NEAR(read_allan_input(jitter, opt).front().tau0_s, 0.01, 1e-5);
  // 200 samples missing (5 % of the record) after line 1000
  const std::string holes = write("holes.txt", [](int i) { return 100.0 + 0.01 * (i < 1000 ? i : i + 200); });
  const std::string e = error_of([&] { read_allan_input(holes, opt); });
  EXPECT_NE(e.find("holes.txt:1001: 1 holes"), std::string::npos) << e;
  // one sample missing: said, analysed
  const std::string one = write("one_hole.txt", [](int i) { return 100.0 + 0.01 * (i < 1000 ? i : i + 1); });
  EXPECT_NEAR(read_allan_input(one, opt).front().tau0_s, 0.01, 1e-9);
}

namespace ldv::allan {
namespace {
// Issue 49: `ldv allan static_7min.csv --columns gx,gy,gz` failed ("no column 'gx' (the header names: Fs, 100)") on
// the real MPU-6050 log that `ldv calib static` reads: four preamble lines come before its header. The layout is now
// read from the file (common/io/delimited_table). Its first row after the header, line 6, is gx -429, gy 140, gz -53
// (counts), and the mean of gz is the log's own.
TEST(AllanInput, GivenTheRealMpu6050LogWithAPreambleBeforeItsHeader_ThenTheNamedColumnsAreRead) {
  const std::string path = std::string(LDV_SHARED_DATA_DIR) + "/calib/mpu6050/static_7min.csv";
  InputOptions csv;
  csv.format = InputFormat::kCsv;
  csv.rate_hz = 100;
  csv.columns = {"gx", "gy", "gz"};
  const std::vector<PhaseSeries> s = read_allan_input(path, csv);
  ASSERT_EQ(s.size(), 3u);
  EXPECT_EQ(s[0].name, "gx");
  EXPECT_EQ(s[2].name, "gz");
  // The test's own reading of the file: every line after the header, the 6th field.
  std::ifstream in(path);
  std::string line;
  long rows = 0;
  double sum_gz = 0.0;
  for (int k = 0; std::getline(in, line); ++k) {
    if (k < 5) continue;
    sum_gz += std::stod(line.substr(line.rfind(',') + 1));
    ++rows;
  }
  ASSERT_GT(rows, 40000);
  EXPECT_EQ(static_cast<long>(s[2].x.size()), rows + 1);  // phase: one more than the rates
  EXPECT_NEAR(s[2].mean_rate, sum_gz / rows, 1e-9 * std::abs(sum_gz / rows));
}
}  // namespace
}  // namespace ldv::allan
