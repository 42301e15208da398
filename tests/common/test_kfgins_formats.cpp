// KF-GINS text formats: round trips and the errors a user gets for bad files.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/formats/kfgins_config.hpp"
#include "common/formats/kfgins_files.hpp"
#include "common/io/input_error.hpp"
#include <functional>

using namespace ldv;
namespace fs = std::filesystem;

namespace {
std::string write_temp(const std::string& name, const std::string& text) {
  const fs::path p = fs::temp_directory_path() / ("ldv_test_" + name);
  std::ofstream(p) << text;
  return p.string();
}
std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(KfGinsFiles, ImuRoundTripKeepsFullPrecision) {
  std::vector<ImuIncrement> imu(3);
  for (int i = 0; i < 3; ++i) {
    imu[i].t_s = 1000.0 + 0.005 * i;
    imu[i].dtheta_b_rad = Vec3(1e-7 * i, -2.5e-4, 3.14159e-3);
    imu[i].dvel_b_mps = Vec3(0.01, -0.02 * i, -0.049);
  }
  const std::string p = write_temp("imu.txt", "");
  write_kfgins_imu(p, imu);
  const auto back = read_kfgins_imu(p);
  ASSERT_EQ(back.size(), 3u);
  EXPECT_NEAR(back[2].dt_s, 0.005, 1e-9);
  EXPECT_NEAR(back[0].dt_s, 0.005, 1e-9);
  EXPECT_DOUBLE_EQ(back[2].dtheta_b_rad.z(), 3.14159e-3);
  EXPECT_DOUBLE_EQ(back[1].dvel_b_mps.y(), -0.02);
}

TEST(KfGinsFiles, BadImuRowsNameFileLineAndColumn) {
  const std::string p1 = write_temp("bad1.txt", "1 0 0 0 0 0 0\n2 0 0 abc 0 0 0\n");
  EXPECT_NE(error_of([&] { read_kfgins_imu(p1); }).find("bad1.txt:2: column 4"), std::string::npos);
  const std::string p2 = write_temp("bad2.txt", "1 0 0 0 0 0 0\n2 0 0 0 0 0\n");
  EXPECT_NE(error_of([&] { read_kfgins_imu(p2); }).find(":2: expected 7 columns (imudatalen), found 6"), std::string::npos);
  const std::string p3 = write_temp("bad3.txt", "2 0 0 0 0 0 0\n1 0 0 0 0 0 0\n");
  EXPECT_NE(error_of([&] { read_kfgins_imu(p3); }).find(":2: time goes backwards"), std::string::npos);
  const std::string p4 = write_temp("bad4.txt", "1 0 0 nan 0 0 0\n");
  EXPECT_NE(error_of([&] { read_kfgins_imu(p4); }).find("finite"), std::string::npos);
  const std::string p5 = write_temp("empty.txt", "");
  EXPECT_NE(error_of([&] { read_kfgins_imu(p5); }).find("no IMU samples"), std::string::npos);
}

TEST(KfGinsFiles, GnssSevenOrThirteenColumns) {
  // One layout per file (the first data line decides): a line of the other layout is a corrupted line.
  const auto g7 = read_kfgins_gnss(write_temp("gnss7.txt", "100.0 30.1 114.2 20.0 0.01 0.02 0.03\n"));
  ASSERT_EQ(g7.size(), 1u);
  EXPECT_FALSE(g7[0].has_velocity);
  const auto g = read_kfgins_gnss(write_temp("gnss13.txt", "101.0 30.1 114.2 20.0 1 2 3 0.01 0.02 0.03 0.1 0.2 0.3\n"));
  ASSERT_EQ(g.size(), 1u);
  EXPECT_TRUE(g[0].has_velocity);
  EXPECT_DOUBLE_EQ(g[0].vel_n_mps.z(), 3.0);
  EXPECT_DOUBLE_EQ(g[0].pos_std_ned_m.y(), 0.02);
  const std::string mixed = write_temp("gnss_mix.txt",
                                       "100.0 30.1 114.2 20.0 0.01 0.02 0.03\n"
                                       "101.0 30.1 114.2 20.0 1 2 3 0.01 0.02 0.03 0.1 0.2 0.3\n");
  EXPECT_NE(error_of([&] { read_kfgins_gnss(mixed); }).find("gnss_mix.txt:2: expected 7 columns (as the first data line)"),
            std::string::npos);
}

TEST(KfGinsConfig, AMistypedKeyIsRefusedWithTheNearestValidOne) {
  // A typo used to be silently ignored (the default kept): now the file, the line and the key it meant.
  const std::string base =
      "imupath: a.txt\ngnsspath: b.txt\nimunoise:\n  arw: [1,1,1]\n  vrw: [1,1,1]\n  gbstd: [1,1,1]\n"
      "  abstd: [1,1,1]\n  corrtime: 1\n";
  const std::string top = error_of([&] { load_kfgins_config(write_temp("typo_top.yaml", base + "antleverr: [0,0,0]\n")); });
  EXPECT_NE(top.find("typo_top.yaml:9: unknown key 'antleverr' (did you mean 'antlever'?)"), std::string::npos) << top;
  const std::string noise =
      error_of([&] { load_kfgins_config(write_temp("typo_noise.yaml", base + "  gsstdd: [1,1,1]\n")); });
  EXPECT_NE(noise.find("unknown key 'imunoise.gsstdd' (did you mean 'imunoise.gsstd'?)"), std::string::npos) << noise;
  const std::string ldv = error_of(
      [&] { load_kfgins_config(write_temp("typo_ldv.yaml", base + "ldv:\n  model: ins15\n  align_hypothesis: 12\n")); });
  EXPECT_NE(ldv.find("typo_ldv.yaml:11: unknown key 'ldv.align_hypothesis' (did you mean 'ldv.align_hypotheses'?)"),
            std::string::npos)
      << ldv;
  EXPECT_NO_THROW(load_kfgins_config(write_temp("known_ldv.yaml", base + "ldv:\n  model: ins15\n  imu_latency: off\n")));
}

TEST(KfGinsConfig, ReadsKfGinsKeysInEngineeringUnitsAndReportsWrongTypes) {
  const std::string good = write_temp("good.yaml",
                                      "imupath: a.txt\ngnsspath: b.txt\noutputpath: .\nimudatalen: 7\n"
                                      "imudatarate: 200\nstarttime: 10\nendtime: -1\n"
                                      "initpos: [30, 114, 20]\ninitvel: [0,0,0]\ninitatt: [1, 2, 185]\n"
                                      "imunoise:\n  arw: [0.003,0.003,0.003]\n  vrw: [0.03,0.03,0.03]\n"
                                      "  gbstd: [0.027,0.027,0.027]\n  abstd: [15,15,15]\n"
                                      "  gsstd: [300,300,300]\n  asstd: [300,300,300]\n  corrtime: 4.0\n"
                                      "antlever: [0.1, -0.3, -0.2]\n");
  const KfGinsConfig c = load_kfgins_config(good);
  EXPECT_NEAR(c.imu_noise.arw_rad_per_sqrt_s.x(), 0.003 * kDegToRad / 60.0, 1e-15);
  EXPECT_NEAR(c.imu_noise.accel_bias_std_mps2.x(), 15e-5, 1e-15);
  EXPECT_NEAR(c.imu_noise.corr_time_s, 4 * 3600.0, 1e-9);
  ASSERT_TRUE(c.init_rpy_rad.has_value());
  EXPECT_NEAR(c.init_rpy_rad->z(), (185.0 - 360.0) * kDegToRad, 1e-12);
  EXPECT_FALSE(c.init_gyro_bias_std_rad_s.has_value());

  const std::string bad = write_temp("bad.yaml",
                                     "imupath: a.txt\ngnsspath: b.txt\nimunoise:\n  arw: fast\n"
                                     "  vrw: [1,1,1]\n  gbstd: [1,1,1]\n  abstd: [1,1,1]\n  corrtime: 1\n");
  const std::string msg = error_of([&] { load_kfgins_config(bad); });
  EXPECT_NE(msg.find("bad.yaml:4: key 'imunoise.arw': expected a list of 3 numbers"), std::string::npos) << msg;

  // Save then load gives the same values back.
  const std::string again = write_temp("again.yaml", "");
  save_kfgins_config(c, again);
  const KfGinsConfig c2 = load_kfgins_config(again);
  EXPECT_NEAR(c2.init_rpy_rad->z(), c.init_rpy_rad->z(), 1e-12);
  EXPECT_NEAR(c2.imu_noise.vrw_mps_per_sqrt_s.y(), c.imu_noise.vrw_mps_per_sqrt_s.y(), 1e-15);
  EXPECT_NEAR(c2.antenna_lever_b_m.y(), -0.3, 1e-12);
}
