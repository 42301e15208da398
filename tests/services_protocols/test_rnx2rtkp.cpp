// RTKLIB itself (Debian's rnx2rtkp) run with instantaneous ambiguity resolution on the real RINEX
// pairs in ../shared/data/gnss, with the configuration we deploy, its output read through our
// parser and checked against the known coordinates and the data owner's own RTKLIB solution.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include "common/geo/earth_model.hpp"
#include "common/formats/rtklib_solution.hpp"

using namespace ldv;
using namespace ldv::gnss;

namespace {
constexpr double kRnxDeg_rad = std::numbers::pi / 180.0;
const std::string kGnss = std::string(LDV_SHARED_DATA_DIR) + "/gnss/";
const std::string kConfig = std::string(LDV_SOURCE_DIR) + "/deploy/rtklib/rtkrcv_instantaneous_ar.conf";
const char* kRnx2rtkp = "/usr/bin/rnx2rtkp";

// Runs rnx2rtkp with `args`, writing `out_name` in a fresh temp dir; returns the .pos path.
std::string run_rnx2rtkp(const std::string& args, const std::string& out_name) {
  // One directory per process: concurrent ctest runs from other build trees must not collide.
  const std::filesystem::path dir =
      std::filesystem::path(::testing::TempDir()) / ("ldv_rnx2rtkp_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string out = (dir / out_name).string();
  std::filesystem::remove(out);
  const std::string cmd = std::string(kRnx2rtkp) + " " + args + " -o " + out + " 2>/dev/null";
  std::printf("[ rnx2rtkp ] %s\n", cmd.c_str());
  EXPECT_EQ(std::system(cmd.c_str()), 0);
  return out;
}

struct Accuracy {
  std::size_t epochs = 0, fixed = 0;
  double horizontal_rms_m = 0, vertical_rms_m = 0, max_3d_m = 0;
  Vec3 mean_ned_m = Vec3::Zero();
};

Accuracy against(const std::vector<GnssSolution>& sols, const Geodetic& truth) {
  Accuracy a;
  a.epochs = sols.size();
  for (const auto& s : sols) {
    const Vec3 d = earth::ned_between(truth, s.fix.pos);
    a.fixed += s.fix.quality == GnssQuality::kFixed;
    a.horizontal_rms_m += d.head<2>().squaredNorm();
    a.vertical_rms_m += d.z() * d.z();
    a.max_3d_m = std::max(a.max_3d_m, d.norm());
    a.mean_ned_m += d;
  }
  const double n = static_cast<double>(std::max<std::size_t>(1, a.epochs));
  a.horizontal_rms_m = std::sqrt(a.horizontal_rms_m / n);
  a.vertical_rms_m = std::sqrt(a.vertical_rms_m / n);
  a.mean_ned_m /= n;
  return a;
}

void print(const char* what, const Accuracy& a) {
  std::printf("[ %s ] epochs %zu, fixed %zu (%.1f %%), error vs known: horizontal RMS %.4f m, vertical RMS %.4f m, "
              "max 3D %.4f m, mean NED (%.4f %.4f %.4f) m\n",
              what, a.epochs, a.fixed, 100.0 * a.fixed / std::max<std::size_t>(1, a.epochs), a.horizontal_rms_m,
              a.vertical_rms_m, a.max_3d_m, a.mean_ned_m.x(), a.mean_ned_m.y(), a.mean_ned_m.z());
}
}  // namespace

TEST(Rnx2rtkp, GivenTheSeptentrioPairAndOurConfig_WhenSolvedWithInstantaneousAr_ThenFixedAtTheKnownRoverWithinCentimetres) {
  if (!std::filesystem::exists(kRnx2rtkp)) GTEST_SKIP() << "rtklib not installed";
  const std::string d = kGnss + "rinex_static_septentrio/";
  // Base position from the data README, given as -l (live, rtkrcv reads it from the RTCM stream).
  const std::string pos = run_rnx2rtkp("-k " + kConfig + " -l 35.134707705 136.977577939 104.853 " + d + "rover.obs " +
                                           d + "base.obs " + d + "base.nav",
                                       "septentrio_llh.pos");
  const auto sols = read_rtklib_pos(pos);
  const Geodetic rover{35.13469901 * kRnxDeg_rad, 136.97757549 * kRnxDeg_rad, 104.8626};
  const Geodetic base{35.134707705 * kRnxDeg_rad, 136.977577939 * kRnxDeg_rad, 104.853};
  const Accuracy a = against(sols, rover);
  print("septentrio, our config", a);
  EXPECT_EQ(a.epochs, 301u);  // 08:20:00-08:25:00 at 1 Hz
  EXPECT_GE(a.fixed, a.epochs * 95 / 100);
  EXPECT_LT(a.horizontal_rms_m, 0.02);
  EXPECT_LT(a.vertical_rms_m, 0.03);
  EXPECT_LT(a.max_3d_m, 0.05);
  ASSERT_FALSE(sols.empty());
  EXPECT_TRUE(sols[0].fix.has_velocity);  // out-outvel=on
  EXPECT_LT(sols[0].fix.vel_n_mps.norm(), 0.1);  // static

  // Baseline length: known rover - known base is ~1 m.
  double mean_baseline_m = 0;
  for (const auto& s : sols) mean_baseline_m += earth::ned_between(base, s.fix.pos).norm();
  mean_baseline_m /= static_cast<double>(sols.size());
  const double known_baseline_m = earth::ned_between(base, rover).norm();
  std::printf("[ septentrio ] baseline: solved mean %.4f m, known %.4f m\n", mean_baseline_m, known_baseline_m);
  EXPECT_NEAR(mean_baseline_m, known_baseline_m, 0.01);

  // The data owner's RTKLIB 2.4.3 solution (their config: instantaneous AR, L1+L2, 15 deg).
  const auto theirs = read_rtklib_pos(d + "rover_rtk.pos");
  std::size_t matched = 0;
  double max_diff_m = 0, sum2 = 0;
  for (const auto& s : sols) {
    for (const auto& t : theirs) {
      if (t.time.week != s.time.week || std::abs(t.time.sow_s - s.time.sow_s) > 1e-3) continue;
      const double diff = earth::ned_between(t.fix.pos, s.fix.pos).norm();
      max_diff_m = std::max(max_diff_m, diff);
      sum2 += diff * diff;
      ++matched;
    }
  }
  const Accuracy b = against(theirs, rover);
  print("septentrio, data owner's rover_rtk.pos", b);
  std::printf("[ septentrio ] ours vs data owner's: %zu epochs matched, 3D difference RMS %.4f m, max %.4f m\n",
              matched, std::sqrt(sum2 / std::max<std::size_t>(1, matched)), max_diff_m);
  EXPECT_EQ(matched, sols.size());
  EXPECT_LT(max_diff_m, 0.03);
}

TEST(Rnx2rtkp, GivenTheSeptentrioPair_WhenOutputIsEcefWithWeekTow_ThenTheParserGivesTheSamePositions) {
  if (!std::filesystem::exists(kRnx2rtkp)) GTEST_SKIP() << "rtklib not installed";
  const std::string d = kGnss + "rinex_static_septentrio/";
  // Command-line options only (RTKLIB's defaults otherwise): -e ECEF output, default week/tow time.
  const std::string pos = run_rnx2rtkp("-p 2 -i -f 2 -m 15 -sys G,R,E,J,C -e -l 35.134707705 136.977577939 104.853 " +
                                           d + "rover.obs " + d + "base.obs " + d + "base.nav",
                                       "septentrio_xyz.pos");
  const auto sols = read_rtklib_pos(pos);
  const Accuracy a = against(sols, {35.13469901 * kRnxDeg_rad, 136.97757549 * kRnxDeg_rad, 104.8626});
  print("septentrio, ECEF + week/tow", a);
  EXPECT_EQ(a.epochs, 301u);
  EXPECT_EQ(sols.front().time.week, 2320);
  EXPECT_NEAR(sols.front().time.sow_s, 116400.0, 1e-6);
  EXPECT_GE(a.fixed, a.epochs * 95 / 100);
  EXPECT_LT(a.max_3d_m, 0.05);
}

TEST(Rnx2rtkp, GivenTheGeonetPair_WhenSolvedWithOurConfig_ThenFixedNearTheGeonetCoordinates) {
  if (!std::filesystem::exists(kRnx2rtkp)) GTEST_SKIP() << "rtklib not installed";
  const std::string d = kGnss + "rinex_geonet/";
  const std::string pos = run_rnx2rtkp("-k " + kConfig + " -r -3978241.958 3382840.234 3649900.853 " + d +
                                           "07590920.05o " + d + "30400920.05o " + d + "07590920.05n " + d +
                                           "30400920.05n",
                                       "geonet.pos");
  const auto sols = read_rtklib_pos(pos);
  // Station 0759 in GEONET F5 (ITRF2014, epoch 2020-10-03, /usr/share/rtklib/geonet_F5.pos). The data
  // are from 2005: 15 years of plate motion and the 2011 Tohoku earthquake move the station by
  // decimetres, so this checks the parser and the fix, not centimetres.
  const Geodetic f5{35.160867766 * kRnxDeg_rad, 139.613844940 * kRnxDeg_rad, 68.4545};
  const Accuracy a = against(sols, f5);
  print("geonet 0759-3040, vs GEONET F5 2020", a);
  EXPECT_GE(a.epochs, 110u);  // 1 h at 30 s
  EXPECT_GE(a.fixed, a.epochs * 90 / 100);
  EXPECT_LT(a.max_3d_m, 0.5);
  // Epoch-to-epoch scatter of the fixed solution: centimetres.
  Vec3 mean = Vec3::Zero(), m2 = Vec3::Zero();
  for (const auto& s : sols) mean += earth::ned_between(f5, s.fix.pos);
  mean /= static_cast<double>(sols.size());
  for (const auto& s : sols) m2 += (earth::ned_between(f5, s.fix.pos) - mean).cwiseAbs2();
  const Vec3 scatter = (m2 / static_cast<double>(sols.size())).cwiseSqrt();
  std::printf("[ geonet ] scatter about the mean: N %.4f E %.4f D %.4f m\n", scatter.x(), scatter.y(), scatter.z());
  EXPECT_LT(scatter.head<2>().norm(), 0.02);
  EXPECT_LT(scatter.z(), 0.04);
}
