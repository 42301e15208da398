// Issue 47, item 5: `ldv nav --kfgins-compatible` is KF-GINS fix by fix on a real drive. KF-GINS itself (built
// outside the repository) ran once on the walk in ../shared from a given start; its output, kept with its
// provenance (data/kfgins_walk_0827/PROVENANCE.md), is the reference: every row's position within 1 mm.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "common/math/rotation.hpp"

namespace ldv {
namespace {
namespace fs = std::filesystem;

const fs::path kData = fs::path(__FILE__).parent_path() / "data";

int run(const std::string& args, const fs::path& log) {
  const std::string cmd = std::string(LDV_BIN_DIR) + "/ldv " + args + " > " + log.string() + " 2>&1";
  const int rc = std::system(cmd.c_str());
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

// Seconds of week (rounded to 0.1 ms) -> lat [deg], lon [deg], h [m].
std::map<long, Vec3> positions(const fs::path& nav) {
  std::map<long, Vec3> out;
  std::ifstream in(nav);
  for (std::string line; std::getline(in, line);) {
    std::istringstream row(line);
    double week, sow, lat, lon, h;
    if (row >> week >> sow >> lat >> lon >> h) out[std::lround(sow * 1e4)] = Vec3(lat, lon, h);
  }
  return out;
}

TEST(KfGinsWalk, GivenKfGinsOwnOutputOnTheRealWalk_ThenKfGinsCompatibleMatchesItWithinAMillimetre) {
  const fs::path dir = fs::temp_directory_path() / ("ldv_kfgins_walk_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  // the inputs as the filter takes them, as KF-GINS took them
  ASSERT_EQ(
      run("nav --kfgins-config " + (kData / "walk_0827_mems.yaml").string() + " --imu-latency off --write-inputs " +
              (dir / "in").string() + " --out " + (dir / "walk.nav").string(),
          dir / "write.log"),
      0);
  std::ifstream start_in(kData / "kfgins_walk_0827" / "start.yaml");
  std::stringstream start;
  start << start_in.rdbuf();
  std::string cfg = start.str();
  for (const auto& [key, value] :
       {std::pair<std::string, std::string>{"INPUTS", (dir / "in").string()}, {"OUT", dir.string()}})
    for (size_t at; (at = cfg.find(key)) != std::string::npos;) cfg.replace(at, key.size(), value);
  cfg += "ldv:\n  zupt: false\n  use_gnss_velocity: false\n";
  std::ofstream(dir / "start.yaml") << cfg;
  ASSERT_EQ(run("nav --kfgins-config " + (dir / "start.yaml").string() +
                    " --kfgins-compatible --imu-latency off --out " + (dir / "ldv.nav").string(),
                dir / "nav.log"),
            0);

  const auto reference = positions(kData / "kfgins_walk_0827" / "kfgins_navresult_every20.nav");
  const auto ours = positions(dir / "ldv.nav");
  ASSERT_GT(reference.size(), 700u);
  double worst_m = 0.0;
  long compared = 0;
  for (const auto& [t, ref] : reference) {
    const auto it = ours.find(t);
    ASSERT_NE(it, ours.end()) << "no ldv row at " << t * 1e-4 << " s";
    const Vec3& p = it->second;
    const double north_m = (p.x() - ref.x()) * kDegToRad * 6378137.0;
    const double east_m = (p.y() - ref.y()) * kDegToRad * 6378137.0 * std::cos(ref.x() * kDegToRad);
    worst_m = std::max(worst_m, Vec3(north_m, east_m, p.z() - ref.z()).norm());
    ++compared;
  }
  std::printf("[ info ] %ld KF-GINS rows: largest position difference %.4f mm\n", compared, worst_m * 1e3);
  EXPECT_LT(worst_m, 1e-3);
}

}  // namespace
}  // namespace ldv
