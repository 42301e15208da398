// The `ldv nav` command line as outside scripts use it (issue 3 contract):
//   ldv nav --kfgins-config FILE.yaml [--model NAME] [--add EFFECT]... [--drop EFFECT]... [--out FILE.nav]
// Given a simulated drive written by the simulator (KF-GINS files + RTKLIB .pos), when `ldv nav` runs, then
// it writes <outputpath>/KF_GINS_Navresult.nav (one 11-column line per IMU sample, with the GPS week) plus
// the std and innovation files; the same drive read from the .pos gives the same solution; and bad inputs
// end with a non-zero exit and a message naming the file and line.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/formats/kfgins_files.hpp"
#include "common/geo/earth_model.hpp"
#include "sim/simulator.hpp"

namespace ldv {
namespace {
namespace fs = std::filesystem;

struct Result {
  int code;
  std::string err;
};

Result run_ldv(const std::string& args, const fs::path& dir, const std::string& command = "nav") {
  const std::string err_path = (dir / "stderr.txt").string();
  const std::string cmd = std::string(LDV_BIN_DIR) + "/ldv " + command + " " + args + " --quiet 2> " + err_path;
  const int rc = std::system(cmd.c_str());
  std::ifstream in(err_path);
  std::stringstream ss;
  ss << in.rdbuf();
  return {WIFEXITED(rc) ? WEXITSTATUS(rc) : -1, ss.str()};
}

class NavCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("ldv_nav_cli_" + std::to_string(::getpid()));
    sim::SimRequest req;
    req.grade = "hg1700-typical";
    req.seed = 5;
    req.duration_s = 60.0;
    req.scenario = "drive";
    req.gnss_rate_hz = 5.0;
    sim_ = new sim::SimResult(sim::simulate(req));
    sim::write_outputs(*sim_, (dir_ / "drive").string());
  }
  static void TearDownTestSuite() {
    delete sim_;
    fs::remove_all(dir_);
  }
  static fs::path dir_;
  static sim::SimResult* sim_;
};
fs::path NavCli::dir_;
sim::SimResult* NavCli::sim_ = nullptr;

TEST_F(NavCli, WritesKfginsNavIntoOutputPathWithWeekStdAndInnovations) {
  const fs::path d = dir_ / "drive";
  const Result r = run_ldv("--kfgins-config " + (d / "kfgins.yaml").string(), dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  const fs::path nav = d / "KF_GINS_Navresult.nav";
  ASSERT_TRUE(fs::exists(nav));
  EXPECT_TRUE(fs::exists(d / "KF_GINS_Navresult_std.txt"));
  EXPECT_TRUE(fs::exists(d / "KF_GINS_Navresult_innovations.txt"));
  const auto recs = read_nav(nav.string());
  EXPECT_EQ(recs.size(), sim_->imu.size());  // one line per IMU sample (the given state is at the first)
  EXPECT_EQ(recs.front().week, sim_->request.gps_week) << "ldv.week written by the simulator";
  // Against truth at the end: RTK-level.
  const auto& t = sim_->truth.back();
  EXPECT_NEAR(recs.back().sow_s, t.t_s, 1e-6);
  EXPECT_LT(earth::ned_between(t.pos, recs.back().pos).norm(), 0.1);
  std::ifstream in(nav);
  std::string line;
  std::getline(in, line);
  std::istringstream fields(line);
  int n = 0;
  for (std::string f; fields >> f;) ++n;
  EXPECT_EQ(n, 11) << line;
}

// The issue 15 contract: `ldv smooth --kfgins-config FILE.yaml --out OUT.nav` writes the smoothed solution in the
// .nav layout and OUT_std.txt beside it (plus the separation and the forward solution). A 40 s GNSS outage in
// turns: the smoothed solution inside it is far closer to the truth than the forward one.
TEST(SmoothCli, WritesTheSmoothedNavStdAndSeparation) {
  const fs::path dir = fs::temp_directory_path() / ("ldv_smooth_cli_" + std::to_string(::getpid()));
  sim::SimRequest req;
  req.grade = "hg1700-typical";
  req.seed = 9;
  req.duration_s = 200.0;
  req.scenario = "figure8";
  req.outages = {{100.0, 40.0}};
  sim::SimResult sim = sim::simulate(req);
  sim::write_outputs(sim, (dir / "drive").string());
  const fs::path out = dir / "smoothed.nav";
  const Result r = run_ldv("--kfgins-config " + (dir / "drive" / "kfgins.yaml").string() + " --out " + out.string(), dir,
                           "smooth");
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* f : {"smoothed_std.txt", "smoothed_separation.txt", "smoothed_forward.nav"})
    EXPECT_TRUE(fs::exists(dir / f)) << f;
  const auto smoothed = read_nav(out.string());
  const auto forward = read_nav((dir / "smoothed_forward.nav").string());
  ASSERT_EQ(smoothed.size(), sim.imu.size());
  ASSERT_EQ(forward.size(), smoothed.size());
  const double t0 = sim.truth.front().t_s;
  double worst_smoothed = 0, worst_forward = 0;
  for (size_t i = 0; i < smoothed.size(); ++i) {
    EXPECT_EQ(smoothed[i].sow_s, forward[i].sow_s);
    const double run_t = smoothed[i].sow_s - t0;
    if (run_t < 100.0 || run_t > 140.0) continue;
    const auto& truth = sim.truth[static_cast<size_t>(std::llround(run_t * req.imu_rate_hz))];
    ASSERT_NEAR(truth.t_s, smoothed[i].sow_s, 1e-6);
    worst_smoothed = std::max(worst_smoothed, earth::ned_between(truth.pos, smoothed[i].pos).head<2>().norm());
    worst_forward = std::max(worst_forward, earth::ned_between(truth.pos, forward[i].pos).head<2>().norm());
  }
  std::printf("40 s outage: largest horizontal error forward %.3f m, smoothed %.3f m\n", worst_forward, worst_smoothed);
  EXPECT_LT(worst_smoothed, 0.1 * worst_forward);
  std::ifstream sd(dir / "smoothed_std.txt");
  std::string header, row;
  std::getline(sd, header);
  std::getline(sd, row);
  EXPECT_NE(header.find("std_pos_n"), std::string::npos);
  std::istringstream fields(row);
  int n = 0;
  for (std::string f; fields >> f;) ++n;
  EXPECT_EQ(n, 2 + 9 + 2 * 12) << "week, sow, 9 navigation std, kfgins21's 12 effect states with their std";
  fs::remove_all(dir);
}

TEST_F(NavCli, ModelAddDropOutAndPosInput) {
  const fs::path d = dir_ / "drive";
  const std::string cfg = "--kfgins-config " + (d / "kfgins.yaml").string();
  const Result a = run_ldv(cfg + " --model ins15 --add gnss_position_bias --add lever_arm --drop accel_bias --out " +
                               (dir_ / "a.nav").string(),
                           dir_);
  ASSERT_EQ(a.code, 0) << a.err;
  std::ifstream std_file(dir_ / "a_std.txt");
  std::string header;
  std::getline(std_file, header);
  EXPECT_NE(header.find("gnss_position_bias_n"), std::string::npos) << header;
  EXPECT_NE(header.find("lever_arm_x"), std::string::npos);
  EXPECT_EQ(header.find("accel_bias"), std::string::npos) << header;
  // The RTKLIB .pos of the same fixes gives the same solution (the .pos rounds to 0.1 mm / 1e-9 deg).
  const Result txt = run_ldv(cfg + " --out " + (dir_ / "txt.nav").string(), dir_);
  const Result pos = run_ldv(cfg + " --pos " + (d / "gnss.pos").string() + " --out " + (dir_ / "pos.nav").string(), dir_);
  ASSERT_EQ(txt.code, 0) << txt.err;
  ASSERT_EQ(pos.code, 0) << pos.err;
  const auto r1 = read_nav((dir_ / "txt.nav").string()), r2 = read_nav((dir_ / "pos.nav").string());
  ASSERT_EQ(r1.size(), r2.size());
  double worst = 0;
  for (size_t i = 0; i < r1.size(); i += 50) worst = std::max(worst, earth::ned_between(r1[i].pos, r2[i].pos).norm());
  EXPECT_LT(worst, 0.01);
}

TEST_F(NavCli, BadInputsFailWithFileAndLine) {
  const fs::path d = dir_ / "drive";
  // A non-numeric field on lines 3, 40 and 77 of a copy of imu.txt (3 %): dropped, counted and named by file and
  // line, with a warning (more than 2 %); an error with --strict (issue 13).
  {
    std::ifstream in(d / "imu.txt");
    std::ofstream out(dir_ / "bad_imu.txt");
    std::string line;
    for (int i = 1; std::getline(in, line) && i <= 100; ++i) out << (i % 37 == 3 ? line + "x" : line) << "\n";
  }
  const std::string bad_imu_args = "--kfgins-config " + (d / "kfgins.yaml").string() + " --imu " +
                                   (dir_ / "bad_imu.txt").string() + " --out " + (dir_ / "b.nav").string();
  Result r = run_ldv(bad_imu_args, dir_);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("bad_imu.txt:3: column 7"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("WARNING: IMU file dropped 3.0 %"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("3 malformed (first: " + (dir_ / "bad_imu.txt").string() + ":3: column 7"), std::string::npos)
      << r.err;
  r = run_ldv(bad_imu_args + " --strict", dir_);
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("--strict: the inputs are not clean"), std::string::npos) << r.err;
  // A configuration key of the wrong type, with its line.
  {
    std::ifstream in(d / "kfgins.yaml");
    std::ofstream out(dir_ / "bad.yaml");
    std::string line;
    while (std::getline(in, line)) out << (line.rfind("starttime:", 0) == 0 ? "starttime: soon" : line) << "\n";
  }
  r = run_ldv("--kfgins-config " + (dir_ / "bad.yaml").string() + " --out " + (dir_ / "c.nav").string(), dir_);
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("bad.yaml:"), std::string::npos) << r.err;
  // An unknown effect, a missing file, no inputs at all.
  r = run_ldv("--kfgins-config " + (d / "kfgins.yaml").string() + " --add wheel_slip --out " + (dir_ / "d.nav").string(),
              dir_);
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("unknown effect 'wheel_slip'"), std::string::npos) << r.err;
  r = run_ldv("--kfgins-config " + (dir_ / "missing.yaml").string(), dir_);
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("missing.yaml"), std::string::npos) << r.err;
  r = run_ldv("", dir_);
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("--kfgins-config"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace ldv
