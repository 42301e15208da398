// Issue 49: a drive as its owner published it runs through `ldv nav` with a table description only. The published
// CSV of a real car is imitated from a simulated drive with truth: one file, 100 Hz rows of an MRU-style IMU in g and
// deg/s in front-left-up axes, a time column that steps by 0.1 s while the rows come at 100 Hz, and the RTK
// positions sample-and-hold in every row (a new fix every 20 rows, blank before the first) with no std. The same
// rows converted by hand into KF-GINS imu.txt / gnss.txt, as the user had to before, give the reference solution.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "common/formats/imu_calibration.hpp"
#include "common/formats/kfgins_config.hpp"
#include "common/formats/kfgins_files.hpp"
#include "common/geo/earth_model.hpp"
#include "input/drive_sources.hpp"
#include "sim/simulator.hpp"
#include "tests/estimator/ldv_output.hpp"
#include "toolbox/assess/nav_inputs.hpp"

namespace ldv::est {
namespace {

namespace fs = std::filesystem;

double compare_json_number(const std::string& json, const std::string& component, const std::string& field) {
  const size_t c = json.find("\"" + component + "\"");
  const size_t f = json.find("\"" + field + "\":", c);
  return c == std::string::npos || f == std::string::npos ? NAN : std::stod(json.substr(f + field.size() + 3));
}

TEST(UserTables, GivenACarsPublishedCsvDescribedInTheConfiguration_ThenLdvNavMatchesTheHandConvertedFiles) {
  sim::SimRequest r;
  r.grade = "3dm-gx2-typical";
  r.seed = 3;
  r.duration_s = 300.0;
  r.imu_rate_hz = 100.0;
  r.gnss_rate_hz = 5.0;
  const sim::SimResult s = sim::simulate(r);
  const fs::path dir = fs::temp_directory_path() / ("ldv_user_tables_" + std::to_string(::getpid()));
  fs::create_directories(dir);

  // The published file, and the hand conversion of its rows (KF-GINS: increments in front-right-down).
  const double t0 = s.imu.front().t_s;
  std::ofstream csv(dir / "GNSS.csv");
  csv << "Time,Acc_X,Acc_Y,Acc_Z,Gyro_X,Gyro_Y,Gyro_Z,Lat_GNSS,Long_GNSS,Height_GNSS\n";
  std::vector<ImuIncrement> hand_imu;
  std::vector<GnssFix> hand_gnss;
  size_t fix = 0;
  long blank_rows = 0;
  for (size_t k = 0; k < s.imu.size(); ++k) {
    const ImuIncrement& inc = s.imu[k];
    const double t = t0 + 0.01 * static_cast<double>(k);  // the rows' true time; the file's column lies
    const Vec3 w_flu_deg_s = Vec3(1, -1, -1).cwiseProduct(inc.dtheta_b_rad) / inc.dt_s / kDegToRad;
    const Vec3 f_flu_g = Vec3(1, -1, -1).cwiseProduct(inc.dvel_b_mps) / inc.dt_s / earth::kStandardGravity_mps2;
    char line[512];
    std::snprintf(line, sizeof line, "%.1f,%.9f,%.9f,%.9f,%.8f,%.8f,%.8f", std::floor(10.0 * (t - t0)) / 10.0,
                  f_flu_g.x(), f_flu_g.y(), f_flu_g.z(), w_flu_deg_s.x(), w_flu_deg_s.y(), w_flu_deg_s.z());
    csv << line;
    // What the user reads back from the printed digits (the hand conversion starts from the file, as the table does).
    Vec3 w, f;
    std::sscanf(line, "%*f,%lf,%lf,%lf,%lf,%lf,%lf", &f.x(), &f.y(), &f.z(), &w.x(), &w.y(), &w.z());
    ImuIncrement h;
    h.t_s = t;
    h.dt_s = 0.01;
    h.dtheta_b_rad = Vec3(1, -1, -1).cwiseProduct(w) * kDegToRad * 0.01;
    h.dvel_b_mps = Vec3(1, -1, -1).cwiseProduct(f) * earth::kStandardGravity_mps2 * 0.01;
    if (k > 0) hand_imu.push_back(h);  // the table's first row starts its clock
    while (fix + 1 < s.gnss.size() && s.gnss[fix + 1].t_s <= t + 1e-6) ++fix;
    if (s.gnss[fix].t_s <= t + 1e-6 && s.gnss[fix].t_s >= t0 + 1.0) {  // the receiver's first fix after 1 s
      const GnssFix& g = s.gnss[fix];
      std::snprintf(line, sizeof line, ",%.10f,%.10f,%.4f\n", g.pos.lat_rad / kDegToRad, g.pos.lon_rad / kDegToRad,
                    g.pos.h_m);
      if (hand_gnss.empty() || hand_gnss.back().t_s < g.t_s - 1e-6) {
        GnssFix hg;
        hg.t_s = t;
        std::sscanf(line, ",%lf,%lf,%lf", &hg.pos.lat_rad, &hg.pos.lon_rad, &hg.pos.h_m);
        hg.pos.lat_rad *= kDegToRad;
        hg.pos.lon_rad *= kDegToRad;
        hg.pos_std_ned_m = Vec3(0.02, 0.02, 0.04);  // the user's assumed std: the file has none
        hand_gnss.push_back(hg);
      }
    } else {
      std::snprintf(line, sizeof line, ",,,\n");  // before the first fix
      ++blank_rows;
    }
    csv << line;
  }
  csv.close();
  write_kfgins_imu((dir / "imu.txt").string(), hand_imu);
  write_kfgins_gnss((dir / "gnss.txt").string(), hand_gnss, false);

  KfGinsConfig hand = s.kfgins;
  hand.ldv = YAML::Node();
  hand.imu_path = (dir / "imu.txt").string();
  hand.gnss_path = (dir / "gnss.txt").string();
  hand.imu_rate_hz = 100.0;
  hand.end_time_s = -1;
  save_kfgins_config(hand, (dir / "hand.yaml").string());
  // The table description: the same configuration without imupath / gnsspath.
  std::ifstream in(dir / "hand.yaml");
  std::ofstream table(dir / "table.yaml");
  for (std::string l; std::getline(in, l);)
    if (l.rfind("imupath:", 0) != 0 && l.rfind("gnsspath:", 0) != 0) table << l << "\n";
  char offset[64];
  std::snprintf(offset, sizeof offset, "%.3f", t0);
  table << "ldv:\n"
        << "  imu_table:\n    path: GNSS.csv\n    time: {row_period_s: 0.01, offset_s: " << offset << "}\n"
        << "    gyro: {columns: [Gyro_X, Gyro_Y, Gyro_Z], unit: deg/s}\n"
        << "    accel: {columns: [Acc_X, Acc_Y, Acc_Z], unit: g}\n"
        << "    axes: [1, -2, -3]\n    sample: interval_mean\n"
        << "  gnss_table:\n    path: GNSS.csv\n    time: {row_period_s: 0.01, offset_s: " << offset << "}\n"
        << "    position: {columns: [Lat_GNSS, Long_GNSS, Height_GNSS]}\n"
        << "    std_m: [0.02, 0.02, 0.04]\n    repeated: drop\n";
  table.close();
  sim::SimResult copy = s;
  sim::write_outputs(copy, (dir / "sim").string());  // truth.nav

  const std::string week = " --week " + std::to_string(r.gps_week);
  const std::string log = test::ldv_output("nav" + week + " --kfgins-config " + (dir / "table.yaml").string() +
                                           " --out " + (dir / "table.nav").string());
  std::printf("%s\n", log.c_str());
  test::ldv_output("nav --quiet" + week + " --kfgins-config " + (dir / "hand.yaml").string() + " --out " +
                   (dir / "hand.nav").string());
  ASSERT_TRUE(fs::exists(dir / "table.nav")) << log;
  EXPECT_NE(log.find(std::to_string(hand_gnss.size()) + " records kept"), std::string::npos) << "every fix, once";
  EXPECT_NE(log.find("sample-and-hold rows dropped"), std::string::npos) << log;
  EXPECT_NE(log.find(std::to_string(blank_rows) + " dropped"), std::string::npos) << "the rows before the first fix";

  const std::string same =
      test::ldv_output("compare --json " + (dir / "table.nav").string() + " " + (dir / "hand.nav").string());
  const std::string truth_t =
      test::ldv_output("compare --json " + (dir / "table.nav").string() + " " + (dir / "sim/truth.nav").string());
  const std::string truth_h =
      test::ldv_output("compare --json " + (dir / "hand.nav").string() + " " + (dir / "sim/truth.nav").string());
  for (const char* c : {"north", "east", "down"}) {
    const double diff = compare_json_number(same, c, "max_abs");
    const double table_rms = compare_json_number(truth_t, c, "rms"), hand_rms = compare_json_number(truth_h, c, "rms");
    std::printf("[ info ] %s: table vs hand-converted at most %.4f m; against truth RMS %.4f vs %.4f m\n", c, diff,
                table_rms, hand_rms);
    EXPECT_LT(diff, 0.01) << c << ": " << same;
    EXPECT_LT(std::abs(table_rms - hand_rms), 0.01) << c;
    EXPECT_LT(table_rms, 0.2) << c << ": the drive is tracked\n" << truth_t;
  }
  fs::remove_all(dir);
}

// Issue 49: the date and the time of day in two fields, as a whitespace-separated log prints RTKLIB's
// "2024/08/27 17:30:01.123" (`time: {date_column: date, column: time, format: gpst}`): the same seconds of week as
// the one-field stamp above, 235800 s at 17:30:00 GPST on Tuesday 2024-08-27 (2 days x 86400 + 63000 s); a date column
// without its format is refused naming the key.
TEST(UserTables, GivenTheDateAndTheTimeInTwoFields_ThenTheRowsAreAtTheirGpsSecondsOfWeek) {
  const fs::path dir = fs::temp_directory_path() / ("ldv_user_tables_two_fields_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  {
    std::ofstream log(dir / "log.txt");
    log << "date time gx gy gz ax ay az\n";
    for (int k = 0; k < 300; ++k) {
      char stamp[64];
      std::snprintf(stamp, sizeof stamp, "2024/08/27 17:30:%02d.%02d", k / 100, k % 100);
      log << stamp << " 0 0 0 0 0 -1\n";
    }
  }
  const auto config = [&](const std::string& time) {
    std::ofstream(dir / "c.yaml") << "gnsspath: gnss.txt\n"
                                  << "imunoise:\n  arw: [1, 1, 1]\n  vrw: [1, 1, 1]\n  gbstd: [10, 10, 10]\n"
                                  << "  abstd: [100, 100, 100]\n  gsstd: [0, 0, 0]\n  asstd: [0, 0, 0]\n  corrtime: 1\n"
                                  << "ldv:\n  imu_table:\n    path: log.txt\n"
                                  << "    time: " << time << "\n"
                                  << "    gyro: {columns: [gx, gy, gz], unit: deg/s}\n"
                                  << "    accel: {columns: [ax, ay, az], unit: g}\n";
    std::ofstream(dir / "gnss.txt") << "235818.0 40.0 -105.0 1600.0 0.02 0.02 0.04\n";
    return load_kfgins_config((dir / "c.yaml").string());
  };
  KfGinsConfig two_fields = config("{date_column: date, column: time, format: gpst}");
  const input::DriveSources read = input::read_drive_sources(input::SourceArgs{}, two_fields);
  ASSERT_EQ(read.imu.size(), 299u);
  EXPECT_NEAR(read.imu.front().t_s, 235800.01, 1e-6);
  EXPECT_NEAR(read.imu.back().t_s, 235802.99, 1e-6);
  try {
    KfGinsConfig no_format = config("{date_column: date, column: time, unit: s}");
    input::read_drive_sources(input::SourceArgs{}, no_format);
    ADD_FAILURE() << "a date column without a format was accepted";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("date_column"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace ldv::est

namespace ldv::est {
namespace {

// A wrong description is refused naming the configuration file, the line and the user's own key, with what was
// expected; a column the file lacks is refused naming the data file and listing its header.
TEST(UserTables, GivenAWrongDescription_ThenTheErrorNamesTheFileLineAndKey) {
  const fs::path dir = fs::temp_directory_path() / ("ldv_user_tables_err_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "log.csv") << "t,gx,gy,gz,ax,ay,az,lat,lon,h\n0,0,0,0,0,0,1,40,-105,1600\n"
                                 << "0.01,0,0,0,0,0,1,40,-105,1600\n";
  const auto error_of = [&](const std::string& imu_table, const std::string& gnss_table) {
    std::ofstream(dir / "c.yaml") << "imunoise:\n  arw: [1, 1, 1]\n  vrw: [1, 1, 1]\n  gbstd: [10, 10, 10]\n"
                                  << "  abstd: [100, 100, 100]\n  gsstd: [0, 0, 0]\n  asstd: [0, 0, 0]\n  corrtime: 1\n"
                                  << "ldv:\n  imu_table:\n"
                                  << imu_table << "  gnss_table:\n"
                                  << gnss_table;
    assess::NavInputArgs a;
    a.config = (dir / "c.yaml").string();
    try {
      assess::load_nav_inputs(a);
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string imu_ok =
      "    path: log.csv\n    time: {column: t}\n    gyro: {columns: [gx, gy, gz], unit: deg/s}\n"
      "    accel: {columns: [ax, ay, az], unit: g}\n";
  const std::string gnss_ok =
      "    path: log.csv\n    time: {column: t}\n    position: {columns: [lat, lon, h]}\n"
      "    std_m: [0.02, 0.02, 0.04]\n";
  const std::string config = (dir / "c.yaml").string();
  const std::string unit = error_of(
      "    path: log.csv\n    time: {column: t}\n    gyro: {columns: [gx, gy, gz], unit: dps}\n"
      "    accel: {columns: [ax, ay, az], unit: g}\n",
      gnss_ok);
  EXPECT_NE(unit.find(config + ":13: ldv.imu_table.gyro.unit"), std::string::npos) << unit;
  EXPECT_NE(unit.find("deg/s"), std::string::npos) << unit;
  const std::string no_std = error_of(imu_ok,
                                      "    path: log.csv\n    time: {column: t}\n"
                                      "    position: {columns: [lat, lon, h]}\n");
  EXPECT_NE(no_std.find("ldv.gnss_table.std_m"), std::string::npos) << no_std;
  const std::string format = error_of(
      "    path: log.csv\n    time: {column: t, format: local}\n    gyro: {columns: [gx, gy, gz], unit: deg/s}\n"
      "    accel: {columns: [ax, ay, az], unit: g}\n",
      gnss_ok);
  EXPECT_NE(format.find("ldv.imu_table.time.format"), std::string::npos) << format;
  EXPECT_NE(format.find("utc"), std::string::npos) << "the choices: " << format;
  const std::string typo = error_of(imu_ok + "    axis: [1, 2, 3]\n", gnss_ok);
  EXPECT_NE(typo.find("ldv.imu_table.axis"), std::string::npos) << typo;
  EXPECT_NE(typo.find("axes"), std::string::npos) << "the nearest key: " << typo;
  const std::string column = error_of(
      "    path: log.csv\n    time: {column: t}\n    gyro: {columns: [Gyro_X, gy, gz], unit: deg/s}\n"
      "    accel: {columns: [ax, ay, az], unit: g}\n",
      gnss_ok);
  EXPECT_NE(column.find((dir / "log.csv").string() + ":1: ldv.imu_table.gyro.columns: no column 'Gyro_X' (the header "
                                                     "names: t, gx, gy, gz, ax, ay, az, lat, lon, h)"),
            std::string::npos)
      << column;
  EXPECT_EQ(error_of(imu_ok, gnss_ok).find("ldv.imu_table"), std::string::npos) << "a right description is read";
  fs::remove_all(dir);
}

}  // namespace
}  // namespace ldv::est

namespace ldv::est {
namespace {

// A calibration from `ldv calib static` is in the device's axes: a table in other axes is calibrated before its axes
// are turned to front-right-down (as the tagged CSV is). A front-left-up device at rest, level, whose y accelerometer
// reads 0.05 g of bias: with the calibration the increments hold gravity alone, in front-right-down.
TEST(UserTables, GivenATableInOtherAxesAndACalibration_ThenItIsAppliedInTheDeviceAxes) {
  const fs::path dir = fs::temp_directory_path() / ("ldv_user_tables_cal_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  {
    std::ofstream csv(dir / "still.csv");
    csv << "t,gx,gy,gz,ax,ay,az\n";
    for (int k = 0; k < 200; ++k) csv << 0.01 * k << ",0,0,0,0,0.05,1\n";  // up is +z: f = +g; y biased
  }
  calib::ImuCalibration cal;
  cal.accel.bias = Vec3(0.0, 0.05 * earth::kStandardGravity_mps2, 0.0);  // device axes
  calib::save_calibration((dir / "cal.yaml").string(), cal);
  std::ofstream(dir / "c.yaml") << "gnsspath: gnss.txt\n"
                                << "imunoise:\n  arw: [1, 1, 1]\n  vrw: [1, 1, 1]\n  gbstd: [10, 10, 10]\n"
                                << "  abstd: [100, 100, 100]\n  gsstd: [0, 0, 0]\n  asstd: [0, 0, 0]\n  corrtime: 1\n"
                                << "ldv:\n  calibration: cal.yaml\n  imu_table:\n    path: still.csv\n"
                                << "    time: {column: t}\n    gyro: {columns: [gx, gy, gz], unit: deg/s}\n"
                                << "    accel: {columns: [ax, ay, az], unit: g}\n    axes: [1, -2, -3]\n";
  std::ofstream(dir / "gnss.txt") << "0.0 40.0 -105.0 1600.0 0.02 0.02 0.04\n1.0 40.0 -105.0 1600.0 0.02 0.02 0.04\n";
  KfGinsConfig cfg = load_kfgins_config((dir / "c.yaml").string());
  const input::DriveSources read = input::read_drive_sources(input::SourceArgs{}, cfg);
  ASSERT_FALSE(read.imu.empty());
  ASSERT_TRUE(read.calibration.has_value());
  const ImuIncrement& s = read.imu.back();
  const Vec3 f_frd = s.dvel_b_mps / s.dt_s;
  std::printf("[ info ] specific force in front-right-down: %.4f %.4f %.4f m/s^2\n", f_frd.x(), f_frd.y(), f_frd.z());
  EXPECT_NEAR(f_frd.x(), 0.0, 1e-9);
  EXPECT_NEAR(f_frd.y(), 0.0, 1e-9) << "the bias taken out on the device's y, before y became -right";
  EXPECT_NEAR(f_frd.z(), -earth::kStandardGravity_mps2, 1e-9);  // up in front-right-down
  fs::remove_all(dir);
}

// A logger that stamps its rows with the date and time of day (UTC, ISO 8601, or local with its zone; GPS time as
// RTKLIB prints it): `time: {column: NAME, format: utc|gpst}` reads them as GPS seconds of week. Truth by hand:
// Tuesday 2024-08-27 17:30:00 UTC is 2 days 17.5 h into GPS week 2329 plus the 18 leap seconds: 235818 s.
TEST(UserTables, GivenDateTimeStampsInUtcLocalOrGpst_ThenTheRowsAreAtTheirGpsSecondsOfWeek) {
  const fs::path dir = fs::temp_directory_path() / ("ldv_user_tables_dates_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  struct Variant {
    const char* name;
    std::string stamp;  // printf pattern of the stamp, given the centiseconds past 17:30:00 (or 19:30:00 local)
    const char* format;
    double first_row_sow_s;
  };
  const Variant variants[] = {{"utc", "2024-08-27T17:30:%02d.%02dZ", "utc", 235818.0},
                              {"local", "2024-08-27 19:30:%02d.%02d+02:00", "utc", 235818.0},
                              {"gpst", "2024/08/27 17:30:%02d.%02d", "gpst", 235800.0}};
  for (const Variant& v : variants) {
    {
      std::ofstream csv(dir / "log.csv");
      csv << "stamp,gx,gy,gz,ax,ay,az\n";
      for (int k = 0; k < 300; ++k) {
        char stamp[64];
        std::snprintf(stamp, sizeof stamp, v.stamp.c_str(), k / 100, k % 100);
        csv << stamp << ",0,0,0,0,0,-1\n";
      }
    }
    std::ofstream(dir / "c.yaml") << "gnsspath: gnss.txt\n"
                                  << "imunoise:\n  arw: [1, 1, 1]\n  vrw: [1, 1, 1]\n  gbstd: [10, 10, 10]\n"
                                  << "  abstd: [100, 100, 100]\n  gsstd: [0, 0, 0]\n  asstd: [0, 0, 0]\n  corrtime: 1\n"
                                  << "ldv:\n  imu_table:\n    path: log.csv\n"
                                  << "    time: {column: stamp, format: " << v.format << "}\n"
                                  << "    gyro: {columns: [gx, gy, gz], unit: deg/s}\n"
                                  << "    accel: {columns: [ax, ay, az], unit: g}\n";
    std::ofstream(dir / "gnss.txt") << "235818.0 40.0 -105.0 1600.0 0.02 0.02 0.04\n";
    KfGinsConfig cfg = load_kfgins_config((dir / "c.yaml").string());
    const input::DriveSources read = input::read_drive_sources(input::SourceArgs{}, cfg);
    ASSERT_EQ(read.imu.size(), 299u) << v.name;  // an increment ends at every row after the first
    EXPECT_NEAR(read.imu.front().t_s, v.first_row_sow_s + 0.01, 1e-6) << v.name;
    EXPECT_NEAR(read.imu.back().t_s, v.first_row_sow_s + 2.99, 1e-6) << v.name;
    EXPECT_NEAR(read.imu.back().dt_s, 0.01, 1e-9) << v.name;
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace ldv::est
