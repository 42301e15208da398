// The files `ldv sim` writes: KF-GINS text and YAML read back with the project's readers, the
// answer key, the RTKLIB .pos layout, and the command-line contract (exit codes, nothing half written).
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include <yaml-cpp/yaml.h>

#include "common/formats/kfgins_config.hpp"
#include "common/formats/kfgins_files.hpp"
#include "sim_test_helpers.hpp"

using namespace ldv;
using namespace ldv::sim;
using namespace ldv::sim::test;
namespace fs = std::filesystem;

namespace {
struct Cmd {
  int exit_code;
  std::string output;
};
Cmd run_ldv(const std::string& args) {
  static int calls = 0;  // one log per call: ctest runs tests in parallel processes
  const std::string log =
      (fs::temp_directory_path() / ("ldv_sim_test_cli_" + std::to_string(::getpid()) + "_" + std::to_string(++calls) + ".log"))
          .string();
  const int rc = std::system((std::string(LDV_BIN_DIR) + "/ldv sim " + args + " > " + log + " 2>&1").c_str());
  std::ifstream in(log);
  std::stringstream s;
  s << in.rdbuf();
  fs::remove(log);
  return {WEXITSTATUS(rc), s.str()};
}
}  // namespace

TEST(SimOutputs, KfGinsFilesAndConfigReadBackAndMatchTheTruth) {
  // Given a run written to a directory
  SimRequest q;
  q.grade = "hg1700-typical";
  q.scenario = "turns";
  q.duration_s = 60;
  q.effects = {"lever_arm=0.2,0.1,-1"};
  q.declared_effects = {"time_offset=0.01"};
  q.gnss_velocity = true;
  SimResult r = simulate(q);
  const fs::path dir = temp_dir("outputs");
  write_outputs(r, dir.string());
  // Then the KF-GINS configuration points into it and starts from the truth
  const KfGinsConfig c = load_kfgins_config((dir / "kfgins.yaml").string());
  EXPECT_EQ(c.imu_path, (dir / "imu.txt").string());
  EXPECT_EQ(c.gnss_path, (dir / "gnss.txt").string());
  EXPECT_EQ(c.output_path, dir.string());
  ASSERT_TRUE(c.init_pos && c.init_vel_n_mps && c.init_rpy_rad);
  EXPECT_NEAR(c.init_pos->lat_rad, r.truth[0].pos.lat_rad, 1e-12);
  EXPECT_NEAR(c.init_rpy_rad->z(), r.truth[0].rpy_rad.z(), 1e-10);
  EXPECT_NEAR(c.imu_noise.arw_rad_per_sqrt_s.x(), 0.125 * kDegToRad / 60, 1e-12);
  EXPECT_EQ(c.antenna_lever_b_m, Vec3::Zero());  // hidden
  EXPECT_NEAR(c.ldv["declared_effects_si"]["time_offset"][0].as<double>(), 0.01, 1e-15);
  // the text files hold the same data
  const auto imu = read_kfgins_imu(c.imu_path);
  ASSERT_EQ(imu.size(), r.imu.size());
  EXPECT_LT((imu[100].dtheta_b_rad - r.imu[100].dtheta_b_rad).norm(), 1e-18);
  const auto gnss = read_kfgins_gnss(c.gnss_path);
  ASSERT_EQ(gnss.size(), r.gnss.size());
  EXPECT_TRUE(gnss[0].has_velocity);
  const auto nav = read_nav((dir / "truth.nav").string());
  ASSERT_EQ(nav.size(), r.truth.size());
  EXPECT_NEAR(nav.back().pos.lat_rad, r.truth.back().pos.lat_rad, 1e-12);
  // the answer key holds every injected effect, SI and engineering units
  const YAML::Node key = YAML::LoadFile((dir / "truth_effects.yaml").string());
  EXPECT_NEAR(key["effects"]["lever_arm"]["si"][2].as<double>(), -1.0, 1e-12);
  EXPECT_FALSE(key["effects"]["lever_arm"]["declared"].as<bool>());
  EXPECT_TRUE(key["effects"]["time_offset"]["declared"].as<bool>());
  EXPECT_EQ(key["effects"]["gyro_bias"]["unit"].as<std::string>(), "deg/h,deg/h,deg/h");
  for (const char* f : {"gnss.pos", "gnss.nmea", "imu_device.bin", "truth_errors.txt", "device_schedule.txt"})
    EXPECT_TRUE(fs::exists(dir / f)) << f;
}

TEST(SimOutputs, RtklibPosHasRtklibsLayout) {
  SimRequest q = perfect_request("static", 5.0);
  q.gnss_mode = "float";
  q.with_noise = true;
  q.start_sow_s = 116400.0;  // 2024/06/24 08:20:00 GPST is week 2320, 116400 s
  q.gps_week = 2320;
  SimResult r = simulate(q);
  const fs::path dir = temp_dir("pos");
  write_outputs(r, dir.string());
  std::ifstream in(dir / "gnss.pos");
  std::string line, first_data, header;
  while (std::getline(in, line)) {
    if (line.rfind("%  GPST", 0) == 0) header = line;
    if (!line.empty() && line[0] != '%' && first_data.empty()) first_data = line;
  }
  EXPECT_NE(header.find("latitude(deg) longitude(deg)  height(m)   Q  ns   sdn(m)"), std::string::npos);
  // Then the first record reads like RTKLIB's: calendar GPST time, fixed-width columns, Q = 2 (float).
  ASSERT_GE(first_data.size(), 23u);
  EXPECT_EQ(first_data.substr(0, 23), "2024/06/24 08:20:00.000");
  std::istringstream cols(first_data.substr(23));
  double lat, lon, h, sdn;
  int Q, ns;
  cols >> lat >> lon >> h >> Q >> ns >> sdn;
  EXPECT_NEAR(lat, r.gnss[0].pos.lat_rad * kRadToDeg, 1e-9);
  EXPECT_EQ(Q, 2);
  EXPECT_NEAR(sdn, r.gnss[0].pos_std_ned_m.x(), 1e-4);
  EXPECT_GT(sdn, 0.2);  // float: the reported std is that of the noise simulated
}

TEST(SimCli, ContractRunWritesTheKfGinsSet) {
  const fs::path dir = temp_dir("cli_ok");
  const Cmd c = run_ldv("--grade hg1900-typical --seed 5 --duration 20 --scenario stops --imu-rate 100 --gnss-rate 5 "
                        "--effect lever_arm --effect gyro_bias=1,2,3 --outages 5:3 --quiet --out " + dir.string());
  ASSERT_EQ(c.exit_code, 0) << c.output;
  for (const char* f : {"imu.txt", "gnss.txt", "truth.nav", "kfgins.yaml"}) EXPECT_TRUE(fs::exists(dir / f)) << f;
  EXPECT_EQ(read_kfgins_gnss((dir / "gnss.txt").string()).size(), 101u - 15u);
  EXPECT_EQ(read_kfgins_imu((dir / "imu.txt").string()).size(), 2000u);
}

TEST(SimCli, BadOptionsFailWithTheFieldNamedAndWriteNothing) {
  const fs::path dir = temp_dir("cli_bad");
  struct Case {
    std::string args, message;
  };
  const std::vector<Case> cases = {
      {"--grade hg2000", "--grade: unknown IMU grade 'hg2000': expected one of perfect, hg1700, hg1900, 3dm-gx2, "
                         "3dm-gx2-q-arcsec, hg1700-typical, hg1900-typical, 3dm-gx2-typical, or a grade YAML file"},
      {"--grade /nonexistent/my_imu.yaml", "--grade: cannot read the grade file"},
      {"--effect lever_arm=1,2", "effect 'lever_arm': expected 3 comma-separated values [m,m,m], found 2"},
      {"--outages 10-20", "--outages: expected START:LENGTH[,START:LENGTH...] in seconds, found '10-20'"},
      {"--scenario nowhere.yaml", "nowhere.yaml: scenario: expected a built-in name"},
      {"--imu-rate 0", "--imu-rate: expected an IMU rate in [1, 4000] Hz, found 0"},
  };
  for (const Case& k : cases) {
    const Cmd c = run_ldv("--seed 1 --duration 5 " + k.args + " --out " + dir.string());
    EXPECT_EQ(c.exit_code, 2) << k.args << "\n" << c.output;
    EXPECT_NE(c.output.find(k.message), std::string::npos) << c.output;
    EXPECT_FALSE(fs::exists(dir)) << k.args;
  }
  // Nothing half-written beside it either (no temporary directory left behind).
  for (const auto& e : fs::directory_iterator(dir.parent_path()))
    EXPECT_EQ(e.path().filename().string().find(".ldv_sim_test_cli_bad.partial"), std::string::npos);
}

TEST(SimOutputs, AFailedWriteLeavesNoPartialDirectory) {
  SimResult r = simulate(perfect_request("static", 2.0));
  const fs::path dir = temp_dir("fail_write");
  r.gnss.clear();  // fine to write
  r.kfgins.imu_noise.corr_time_s = 1.0;
  // An output path whose parent is a regular file cannot be created: an InputError, nothing written.
  const std::string blocker = write_text("blocker_file", "x");
  EXPECT_NE(input_error_of([&] { write_outputs(r, blocker + "/out"); }), "");
  EXPECT_FALSE(fs::exists(dir));
}

TEST(SimCli, AGradeFileRunsAndABadOneNamesFileLineAndKey) {
  // --print-grade gives a built-in in the file form; that file as --grade runs; a typo is named with its line.
  const Cmd printed = run_ldv("--print-grade hg1900");
  ASSERT_EQ(printed.exit_code, 0) << printed.output;
  EXPECT_NE(printed.output.find("K_deg_h_sqrt_h: [2.18, 3.126, 1.846]"), std::string::npos) << printed.output;
  const std::string file = write_text("cli_grade.yaml", printed.output);
  const fs::path dir = temp_dir("cli_grade");
  const Cmd ok = run_ldv("--grade " + file + " --seed 3 --duration 5 --scenario static --imu-rate 100 --quiet --out " +
                         dir.string());
  ASSERT_EQ(ok.exit_code, 0) << ok.output;
  EXPECT_EQ(read_kfgins_imu((dir / "imu.txt").string()).size(), 500u);
  const YAML::Node cfg = YAML::LoadFile((dir / "kfgins.yaml").string());
  EXPECT_EQ(cfg["ldv"]["simulator"]["grade"].as<std::string>(), "hg1900");
  // The -paper alias prints the same grade under its own name; a -typical stand-in has no file form.
  const Cmd alias = run_ldv("--print-grade hg1900-paper");
  ASSERT_EQ(alias.exit_code, 0) << alias.output;
  EXPECT_EQ(alias.output.substr(alias.output.find('\n')), printed.output.substr(printed.output.find('\n')));
  const Cmd typical = run_ldv("--print-grade hg1900-typical");
  EXPECT_EQ(typical.exit_code, 2) << typical.output;
  EXPECT_NE(typical.output.find("--print-grade: no file form of the grade 'hg1900-typical': expected one of hg1700, "
                                "hg1900, 3dm-gx2, 3dm-gx2-q-arcsec"),
            std::string::npos)
      << typical.output;

  const std::string bad = write_text("cli_bad_grade.yaml", "name: mine\naccel:\n  N_mps_sqrt_h: 0.1\n  K_mps_h_sqr_h: 1\n");
  const fs::path none = temp_dir("cli_bad_grade_out");
  const Cmd c = run_ldv("--grade " + bad + " --duration 5 --out " + none.string());
  EXPECT_EQ(c.exit_code, 2) << c.output;
  EXPECT_NE(c.output.find(bad + ":4: unknown key 'accel.K_mps_h_sqr_h' (did you mean 'accel.K_mps_h_sqrt_h'?)"),
            std::string::npos)
      << c.output;
  EXPECT_FALSE(fs::exists(none));
  EXPECT_EQ(run_ldv("--print-grade hg2000").exit_code, 2);
}
