// `ldv convert` against the tools people read its files with: a simulated drive with a GNSS outage, run by `ldv nav`,
// converted to GPX, KML and NMEA and read back by gpsbabel (Debian's; it writes its own GPX, parsed here): every point
// it reads is within 5 cm of the solution at its time and within 1 ms of a solution epoch (or of the requested grid),
// and the CSV's header names every column with its unit. The solution itself is read with the strict .nav reader.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "common/formats/kfgins_files.hpp"
#include "common/geo/earth_model.hpp"
#include "common/time/utc_text.hpp"
#include "tests/estimator/ldv_output.hpp"

namespace ldv {
namespace {
namespace fs = std::filesystem;

std::string run(const std::string& command) { return est::test::command_output(command); }
std::string ldv(const std::string& args) { return est::test::ldv_output(args); }

std::string read_text(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

struct ReadBack {
  double t_s;  // GPS seconds of the week of the solution
  Geodetic pos;
};

// gpsbabel's GPX: every track point's lat, lon, ele and UTC time.
std::vector<ReadBack> track_points(const std::string& gpx, int week) {
  std::vector<ReadBack> out;
  const std::regex trkpt(
      R"re(<trkpt lat="([-0-9.]+)" lon="([-0-9.]+)">\s*<ele>([-0-9.]+)</ele>\s*<time>([^<]+)</time>)re");
  for (auto it = std::sregex_iterator(gpx.begin(), gpx.end(), trkpt); it != std::sregex_iterator(); ++it) {
    DateTimeText dt;
    if (!parse_date_time((*it)[4].str(), dt)) ADD_FAILURE() << "gpsbabel time " << (*it)[4].str();
    const GpsTime t = gps_from_utc(dt.calendar);
    ReadBack r;
    r.t_s = (t.week - week) * kSecondsPerWeek + t.sow_s;
    r.pos = {std::stod((*it)[1].str()) * kDegToRad, std::stod((*it)[2].str()) * kDegToRad, std::stod((*it)[3].str())};
    out.push_back(r);
  }
  return out;
}

class ConvertedDrive : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("ldv_convert_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    ldv("sim --grade 3dm-gx2-typical --seed 3 --duration 120 --gnss-rate 5 --outages 60:15 --quiet --out " +
        (dir_ / "sim").string());
    ldv("nav --kfgins-config " + (dir_ / "sim/kfgins.yaml").string() + " --quiet --out " + (dir_ / "run.nav").string());
    nav_ = read_nav((dir_ / "run.nav").string());
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }

  // The solution at t_s (linear between its epochs) and the distance of t_s to the nearest epoch.
  static Geodetic solution_at(double t_s, double* nearest_epoch_s) {
    const auto t_of = [](const NavRecord& r) { return r.sow_s; };
    auto it =
        std::lower_bound(nav_.begin(), nav_.end(), t_s, [&](const NavRecord& r, double t) { return t_of(r) < t; });
    if (it == nav_.end()) it = std::prev(it);
    const auto a = it == nav_.begin() ? it : std::prev(it);
    *nearest_epoch_s = std::min(std::abs(t_of(*a) - t_s), std::abs(t_of(*it) - t_s));
    const double w = t_of(*it) > t_of(*a) ? std::clamp((t_s - t_of(*a)) / (t_of(*it) - t_of(*a)), 0.0, 1.0) : 0.0;
    return {a->pos.lat_rad + w * (it->pos.lat_rad - a->pos.lat_rad),
            a->pos.lon_rad + w * (it->pos.lon_rad - a->pos.lon_rad), a->pos.h_m + w * (it->pos.h_m - a->pos.h_m)};
  }

  // Converts to `format`, has gpsbabel read it back, and checks every point; returns how many it read.
  static size_t check_read_back(const std::string& format, const std::string& rate, double grid_s) {
    const fs::path out = dir_ / ("run." + format), back = dir_ / ("back_" + format + ".gpx");
    const std::string said = ldv("convert " + (dir_ / "run.nav").string() + " --to " + format + " --rate " + rate +
                                 " --out " + out.string());
    EXPECT_TRUE(fs::exists(out)) << said;
    const std::string babel = run("gpsbabel -t -i " + format + " -f " + out.string() + " -o gpx -F " + back.string());
    EXPECT_TRUE(fs::exists(back)) << "gpsbabel: " << babel;
    const std::vector<ReadBack> points = track_points(read_text(back), nav_.front().week);
    double worst_m = 0.0, worst_s = 0.0;
    for (const ReadBack& p : points) {
      double nearest_s = 0.0;
      const Geodetic s = solution_at(p.t_s, &nearest_s);
      const Vec3 d = earth::ned_between(s, p.pos);
      worst_m = std::max(worst_m, d.norm());
      const double off_grid_s = grid_s > 0 ? std::abs(p.t_s - grid_s * std::round(p.t_s / grid_s)) : nearest_s;
      worst_s = std::max(worst_s, off_grid_s);
    }
    std::printf("[ info ] %s at --rate %s: gpsbabel read %zu points, worst %.4f m, %.5f s off\n", format.c_str(),
                rate.c_str(), points.size(), worst_m, worst_s);
    EXPECT_LT(worst_m, 0.05) << format;
    EXPECT_LT(worst_s, 0.001) << format;
    return points.size();
  }

  static fs::path dir_;
  static std::vector<NavRecord> nav_;
};
fs::path ConvertedDrive::dir_;
std::vector<NavRecord> ConvertedDrive::nav_;

TEST_F(ConvertedDrive, GivenEverySolutionEpoch_ThenGpsbabelReadsTheGpxAndKmlBackWithin5cmAnd1ms) {
  ASSERT_GT(nav_.size(), 20000u);
  EXPECT_EQ(check_read_back("gpx", "0", 0.0), nav_.size());
  // KML: one gx:Track per GNSS-aided / INS-only run, each after the first repeating the point before it
  const size_t kml = check_read_back("kml", "0", 0.0);
  EXPECT_GE(kml, nav_.size());
  EXPECT_LE(kml, nav_.size() + 4);
}

TEST_F(ConvertedDrive, GivenTenHertz_ThenGpsbabelReadsTheNmeaBackOnItsGridWithin5cm) {
  const size_t n = check_read_back("nmea", "10", 0.1);
  EXPECT_NEAR(static_cast<double>(n), 10.0 * (nav_.back().sow_s - nav_.front().sow_s), 2.0);
}

TEST_F(ConvertedDrive, GivenTheOutage_ThenTheKmlMarksItsInsOnlySpanAndTheNmeaSaysDeadReckoning) {
  ldv("convert " + (dir_ / "run.nav").string() + " --to kml --out " + (dir_ / "span.kml").string());
  const std::string kml = read_text(dir_ / "span.kml");
  // The outage is 15 s; the solution counts as INS-only from 2 s after the last accepted fix (the filter's rule).
  const std::smatch m = [&] {
    std::smatch s;
    std::regex_search(kml, s, std::regex(R"(<name>INS only ([0-9.]+) s</name>)"));
    return s;
  }();
  ASSERT_FALSE(m.empty()) << kml.substr(0, 2000);
  EXPECT_NEAR(std::stod(m[1].str()), 13.0, 1.5);
  ldv("convert " + (dir_ / "run.nav").string() + " --to nmea --out " + (dir_ / "span.nmea").string());
  const std::string nmea = read_text(dir_ / "span.nmea");
  EXPECT_NE(nmea.find(",6,00,"), std::string::npos) << "no GGA with quality 6 (dead reckoning)";
  EXPECT_NE(nmea.find("$GNHDT,"), std::string::npos);
  EXPECT_NE(nmea.find("$GNGST,"), std::string::npos);
  EXPECT_NE(nmea.find("$GNVTG,"), std::string::npos);
}

TEST_F(ConvertedDrive, GivenCsv_ThenTheHeaderNamesEveryColumnWithItsUnitAndTheRowsAreTheSolution) {
  ldv("convert " + (dir_ / "run.nav").string() + " --to csv --out " + (dir_ / "run.csv").string());
  std::ifstream f(dir_ / "run.csv");
  std::string header, row;
  std::getline(f, header);
  EXPECT_EQ(header,
            "gps_week,gps_sow_s,utc,lat_deg,lon_deg,height_ellipsoid_m,vel_north_mps,vel_east_mps,vel_down_mps,"
            "roll_deg,pitch_deg,yaw_deg,std_north_m,std_east_m,std_down_m,aiding");
  size_t rows = 0;
  double worst_deg = 0.0;
  while (std::getline(f, row)) {
    std::vector<std::string> fields;
    std::stringstream s(row);
    for (std::string x; std::getline(s, x, ',');) fields.push_back(x);
    ASSERT_EQ(fields.size(), 16u) << row;
    const NavRecord& r = nav_.at(rows++);
    worst_deg = std::max({worst_deg, std::abs(std::stod(fields[3]) - r.pos.lat_rad * kRadToDeg),
                          std::abs(std::stod(fields[4]) - r.pos.lon_rad * kRadToDeg)});
    EXPECT_NEAR(std::stod(fields[1]), r.sow_s, 1e-6);
  }
  EXPECT_EQ(rows, nav_.size());
  EXPECT_LT(worst_deg, 1e-8);
}

TEST_F(ConvertedDrive, GivenANavWithoutAWeek_ThenGpxIsRefusedNamingTheFileUntilAWeekIsGiven) {
  // A KF-GINS-style solution: seconds of week only (week 0)
  std::ifstream in(dir_ / "run.nav");
  std::ofstream out(dir_ / "noweek.nav");
  for (std::string line; std::getline(in, line);) out << "0" << line.substr(line.find(' ')) << "\n";
  out.close();
  const std::string said =
      ldv("convert " + (dir_ / "noweek.nav").string() + " --to gpx --out " + (dir_ / "noweek.gpx").string());
  EXPECT_NE(said.find("noweek.nav"), std::string::npos) << said;
  EXPECT_NE(said.find("--week"), std::string::npos) << said;
  ldv("convert " + (dir_ / "noweek.nav").string() + " --to gpx --week " + std::to_string(nav_.front().week) +
      " --out " + (dir_ / "noweek.gpx").string());
  EXPECT_EQ(read_text(dir_ / "noweek.gpx").find("<time>") != std::string::npos, true);
}

}  // namespace
}  // namespace ldv
