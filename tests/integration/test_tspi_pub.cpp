// tspi_pub as a real process in a private network namespace: NAV in at 200 Hz on the vehicle bus,
// TSPI out at the configured 10 Hz on its own multicast group, no gaps, clean exit on SIGTERM.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <ldv_lcm/nav_state_t.hpp>
#include <ldv_lcm/service_status_t.hpp>
#include <ldv_lcm/tspi_v1_t.hpp>
#include <regex>
#include <sstream>
#include <thread>

#include "common/bus/bus.hpp"
#include "common/time/utc_text.hpp"
#include "tests/integration/bus_spin.hpp"
#include "tests/integration/child_process.hpp"
#include "tests/integration/pty_pair.hpp"

using namespace ldv;

TEST(TspiPubIntegration, DecimatesNavToConfiguredRateOnItsGroupAndStopsCleanly) {
  const std::string vehicle_url = "udpm://239.255.76.67:7667?ttl=0";
  const std::string cfg = (std::filesystem::temp_directory_path() / "ldv_tspi_test.yaml").string();
  std::ofstream(cfg) << "bus_url: \"" << vehicle_url << "\"\ntspi:\n  rate_hz: 10\n  group: 239.255.77.1\n"
                     << "  port: 7668\n  ttl: 1\n  channel: TSPI\n";
  test::ChildProcess svc(std::string(LDV_BIN_DIR) + "/tspi_pub", {"--config", cfg});

  Bus vehicle(vehicle_url);
  Bus remote("udpm://239.255.77.1:7668?ttl=1");
  std::vector<ldv_lcm::tspi_v1_t> got;
  bool heartbeat = false;
  remote.subscribe<ldv_lcm::tspi_v1_t>("TSPI", [&](const ldv_lcm::tspi_v1_t& t, const std::string&) { got.push_back(t); });
  vehicle.subscribe<ldv_lcm::service_status_t>("STATUS_TSPI_PUB", [&](const ldv_lcm::service_status_t&, const std::string&) { heartbeat = true; });

  // Given the service is up (its heartbeat arrives; a loaded machine only makes it slower)
  ASSERT_TRUE(test::spin_until(vehicle, [&] { return heartbeat; }, 30.0)) << "no STATUS_TSPI_PUB heartbeat within 30 s";

  // When 3 s of NAV at 200 Hz are published
  ldv_lcm::nav_state_t nav{};
  nav.gps_week = 2300;
  nav.mode = 2;
  for (int k = 0; k < 600; ++k) {
    nav.seq = k;
    nav.gps_sow_s = 1000.0 + k * 0.005;
    nav.lat_deg = 45.0 + 1e-6 * k;
    nav.lon_deg = 7.0;
    nav.pos_std_ned_m[0] = nav.pos_std_ned_m[1] = 0.02f;
    vehicle.publish("NAV", nav);
    remote.handle(0);
    vehicle.handle(0);
    std::this_thread::sleep_for(std::chrono::microseconds(4500));
  }
  test::spin_until(remote, [&] { return got.size() >= 30; }, 30.0);
  test::spin_until(remote, [] { return false; }, 0.2);  // an extra TSPI would follow at once

  // Then TSPI arrives at 10 Hz of GPS time (30 epochs over 3 s), in sequence, at RTK quality
  ASSERT_EQ(got.size(), 30u);
  for (size_t i = 0; i < got.size(); ++i) {
    EXPECT_EQ(got[i].seq, static_cast<int64_t>(i));
    EXPECT_NEAR(got[i].gps_sow_s, 1000.0 + 0.1 * i, 1e-9);
    EXPECT_EQ(got[i].quality, 3);
  }
  // And SIGTERM ends it cleanly
  svc.signal(SIGTERM);
  EXPECT_EQ(svc.wait_exit(3.0), 0);
}

namespace {
// Runs `program args`, returns its exit status and what it wrote to stderr (15 s at most).
std::pair<int, std::string> run_to_exit(const std::string& program, const std::vector<std::string>& args,
                                        const std::string& name) {
  const std::string log = (std::filesystem::temp_directory_path() / ("ldv_" + name + ".log")).string();
  test::ChildProcess p(program, args, "", log);
  const int rc = p.wait_exit(15.0);
  std::ifstream in(log);
  return {rc, std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>())};
}
std::string config_file(const std::string& name, const std::string& text) {
  const std::string path = (std::filesystem::temp_directory_path() / ("ldv_" + name + ".yaml")).string();
  std::ofstream(path) << text;
  return path;
}
}  // namespace

// Issue 35, items 9 and 10: a channel LCM cannot send (300 characters: tspi_pub said ready and never sent) and a
// group with a URL spliced into it (TSPI went to port 9999): refused at start-up, naming the file, line and key.
TEST(TspiPubIntegration, GivenAChannelLcmCannotSendOrAGroupThatIsNotAMulticastAddress_ThenItRefusesToStart) {
  const std::string bin = std::string(LDV_BIN_DIR) + "/tspi_pub";
  const std::string long_channel =
      config_file("tspi_long_channel", "tspi:\n  channel: " + std::string(300, 'T') + "\n");
  auto [rc, err] = run_to_exit(bin, {"--config", long_channel}, "tspi_long_channel");
  EXPECT_EQ(rc, 1);
  EXPECT_NE(err.find(long_channel + ":2: tspi.channel: expected an LCM channel name"), std::string::npos) << err;

  for (const std::string group : {"\"239.255.77.1:9999?ttl=255&x=\"", "10.0.0.1", "239.255.77", "localhost"}) {
    const std::string bad_group = config_file("tspi_bad_group", "tspi:\n  group: " + group + "\n");
    std::tie(rc, err) = run_to_exit(bin, {"--config", bad_group}, "tspi_bad_group");
    EXPECT_EQ(rc, 1) << group;
    EXPECT_NE(err.find(bad_group + ":2: tspi.group: expected an IPv4 multicast address"), std::string::npos) << err;
  }
  // Issue 50: the NMEA output's destination and talker, refused the same way
  const std::string bad_udp = config_file("tspi_bad_nmea_udp", "nmea:\n  udp: 127.0.0.1\n");
  std::tie(rc, err) = run_to_exit(bin, {"--config", bad_udp}, "tspi_bad_nmea_udp");
  EXPECT_EQ(rc, 1);
  EXPECT_NE(err.find(bad_udp + ":2: nmea.udp: expected HOST:PORT"), std::string::npos) << err;
  const std::string bad_talker = config_file("tspi_bad_nmea_talker", "nmea:\n  udp: 127.0.0.1:10110\n  talker: G\n");
  std::tie(rc, err) = run_to_exit(bin, {"--config", bad_talker}, "tspi_bad_nmea_talker");
  EXPECT_EQ(rc, 1);
  EXPECT_NE(err.find(bad_talker + ":3: nmea.talker: expected a two-letter NMEA talker ID"), std::string::npos) << err;
}

// Issue 35, item 8: a tcpq:// bus with no server made fusion and `ldv spy` abort inside LCM (select on fd -1,
// SIGABRT) and `ldv play` exit 0 having published nothing: each now exits 1 saying the bus is not connected.
TEST(BusUrl, GivenATcpqBusWithNoServer_ThenFusionSpyAndPlayExitWithAClearError) {
  const std::string url = "tcpq://127.0.0.1:1";
  const std::string bin = std::string(LDV_BIN_DIR);
  const std::string kfgins = config_file("tcpq_kfgins",
                                         "imupath: imu.txt\ngnsspath: gnss.txt\nimunoise:\n  arw: [0.2, 0.2, 0.2]\n"
                                         "  vrw: [0.4, 0.4, 0.4]\n  gbstd: [50, 50, 50]\n  abstd: [250, 250, 250]\n"
                                         "  corrtime: 1.0\n");
  auto [rc, err] = run_to_exit(bin + "/fusion", {"--bus-url", url, "--kfgins-config", kfgins}, "tcpq_fusion");
  EXPECT_EQ(rc, 1) << err;
  EXPECT_NE(err.find("not connected"), std::string::npos) << err;
  std::tie(rc, err) = run_to_exit(bin + "/ldv", {"spy", "--url", url}, "tcpq_spy");
  EXPECT_EQ(rc, 1) << err;
  EXPECT_NE(err.find("not connected"), std::string::npos) << err;
  // `ldv play` too (issue 46, item 4: the test carried its name but never ran it).
  const std::string run_dir = (std::filesystem::temp_directory_path() / "ldv_tcpq_play_sim").string();
  std::tie(rc, err) = run_to_exit(bin + "/ldv", {"sim", "--out", run_dir, "--duration", "5"}, "tcpq_sim");
  ASSERT_EQ(rc, 0) << err;
  std::tie(rc, err) = run_to_exit(bin + "/ldv", {"play", run_dir, "--url", url, "--week", "2300"}, "tcpq_play");
  EXPECT_EQ(rc, 1) << err;
  EXPECT_NE(err.find("not connected"), std::string::npos) << err;
}

namespace {
// The TPV reports gpspipe printed: GPS seconds of week from their UTC time, latitude, longitude, ellipsoidal height.
struct Tpv {
  double sow_s = 0.0, lat_deg = 0.0, lon_deg = 0.0, h_m = NAN;
  int mode = 0;
};
std::vector<Tpv> tpv_reports(const std::string& json_lines) {
  std::vector<Tpv> out;
  const std::regex field(R"re("(time|lat|lon|altHAE|mode)":("[^"]*"|[-0-9.eE+]+))re");
  std::istringstream lines(json_lines);
  for (std::string line; std::getline(lines, line);) {
    if (line.find("\"class\":\"TPV\"") == std::string::npos) continue;
    Tpv t;
    bool has_time = false, has_lat = false;
    for (auto it = std::sregex_iterator(line.begin(), line.end(), field); it != std::sregex_iterator(); ++it) {
      const std::string key = (*it)[1].str(), value = (*it)[2].str();
      if (key == "time") {
        ldv::DateTimeText dt;
        has_time = ldv::parse_date_time(value.substr(1, value.size() - 2), dt);
        if (has_time) t.sow_s = ldv::gps_from_utc(dt.calendar).sow_s;
      } else if (key == "lat") {
        t.lat_deg = std::stod(value), has_lat = true;
      } else if (key == "lon") {
        t.lon_deg = std::stod(value);
      } else if (key == "altHAE") {
        t.h_m = std::stod(value);
      } else if (key == "mode") {
        t.mode = std::stoi(value);
      }
    }
    if (has_time && has_lat) out.push_back(t);
  }
  return out;
}
}  // namespace

// Issue 50: tspi_pub also speaks NMEA for a downstream device (`nmea: {udp, rate_hz, talker}`), checked by gpsd, the
// daemon such devices and their software read positions through: given NAV at 200 Hz moving north at 22 m/s, gpsd
// decodes tspi_pub's UDP NMEA at the configured 5 Hz into 3-D fixes within 5 cm (and 1 cm of height) of the TSPI of
// the same GPS time.
TEST(TspiPubIntegration, GivenAnNmeaSection_ThenGpsdDecodesItsStreamWithin5cmOfTheTspi) {
  ASSERT_EQ(std::system("command -v gpsd > /dev/null && command -v gpspipe > /dev/null"), 0)
      << "gpsd and gpspipe are needed (scripts/install_deps.sh installs gpsd and gpsd-clients)";
  const std::string vehicle_url = "udpm://239.255.76.67:7667?ttl=0";
  const std::string cfg = config_file("tspi_nmea", "bus_url: \"" + vehicle_url +
                                                       "\"\ntspi:\n  rate_hz: 10\nnmea:\n  udp: 127.0.0.1:10110\n"
                                                       "  rate_hz: 5\n  talker: GP\n");
  const auto tmp = std::filesystem::temp_directory_path();
  test::ChildProcess gpsd("/usr/sbin/gpsd", {"-N", "-n", "-S", "2947", "udp://127.0.0.1:10110"}, "",
                          (tmp / "ldv_gpsd.log").string());
  test::ChildProcess svc(std::string(LDV_BIN_DIR) + "/tspi_pub", {"--config", cfg}, "",
                         (tmp / "ldv_tspi_nmea.log").string());
  Bus vehicle(vehicle_url);
  bool heartbeat = false;
  vehicle.subscribe<ldv_lcm::service_status_t>(
      "STATUS_TSPI_PUB", [&](const ldv_lcm::service_status_t&, const std::string&) { heartbeat = true; });
  ASSERT_TRUE(test::spin_until(
      vehicle, [&] { return heartbeat; }, 30.0))
      << "no STATUS_TSPI_PUB heartbeat within 30 s";
  const std::string reports = (tmp / "ldv_gpspipe.json").string();
  test::ChildProcess pipe("/usr/bin/gpspipe", {"-w", "-n", "200"}, reports);
  std::this_thread::sleep_for(std::chrono::seconds(1));  // gpspipe connected and watching

  const auto lat_at = [](double sow_s) { return 45.0 + 2e-4 * (sow_s - 1000.0); };  // 22.2 m/s north
  ldv_lcm::nav_state_t nav{};
  nav.gps_week = 2300;
  nav.mode = 2;
  nav.lon_deg = 7.0;
  nav.height_m = 250.0;
  nav.vel_ned_mps[0] = 2e-4 * 111132.0;
  for (int k = 0; k < 800; ++k) {
    nav.seq = k;
    nav.gps_sow_s = 1000.0 + k * 0.005;
    nav.lat_deg = lat_at(nav.gps_sow_s);
    nav.pos_std_ned_m[0] = nav.pos_std_ned_m[1] = 0.02f;
    nav.pos_std_ned_m[2] = 0.03f;
    vehicle.publish("NAV", nav);
    vehicle.handle(0);
    std::this_thread::sleep_for(std::chrono::microseconds(4500));
  }
  std::this_thread::sleep_for(std::chrono::seconds(1));
  pipe.signal(SIGTERM);
  pipe.wait_exit(3.0);
  svc.signal(SIGTERM);
  EXPECT_EQ(svc.wait_exit(3.0), 0);
  gpsd.signal(SIGTERM);
  gpsd.wait_exit(3.0);

  std::ifstream in(reports);
  const std::vector<Tpv> tpv =
      tpv_reports(std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()));
  double worst_m = 0.0, worst_h_m = 0.0;
  int three_d = 0;
  for (const Tpv& t : tpv) {
    const double north_m = (t.lat_deg - lat_at(t.sow_s)) * 111132.0;
    const double east_m = (t.lon_deg - 7.0) * 111132.0 * std::cos(45.0 * M_PI / 180.0);
    worst_m = std::max(worst_m, std::hypot(north_m, east_m));
    if (std::isfinite(t.h_m)) worst_h_m = std::max(worst_h_m, std::abs(t.h_m - 250.0));
    three_d += t.mode == 3;
    EXPECT_NEAR(t.sow_s * 5.0, std::round(t.sow_s * 5.0), 1e-3) << "off the 5 Hz grid: " << t.sow_s;
  }
  std::printf("[ info ] gpsd: %zu fixes (%d 3-D), worst horizontal %.4f m, height %.4f m\n", tpv.size(), three_d,
              worst_m, worst_h_m);
  EXPECT_GE(tpv.size(), 15u);  // 4 s at 5 Hz
  EXPECT_GE(three_d, 15);
  EXPECT_LT(worst_m, 0.05);
  EXPECT_LT(worst_h_m, 0.01);
}

// Issue 50, the serial side: the same NMEA on a serial port (a pty here). A reader that does not read for 4 s never
// freezes the service (its heartbeat and TSPI go on), and what it reads afterwards is whole sentences, every one with
// a valid checksum: an epoch the port could not take is dropped whole, never cut.
TEST(TspiPubIntegration, GivenAnNmeaSerialPortWhoseReaderStalls_ThenTheServiceGoesOnAndNoSentenceIsCut) {
  const std::string vehicle_url = "udpm://239.255.76.67:7667?ttl=0";
  test::PtyPair pty;
  const std::string cfg =
      config_file("tspi_nmea_serial", "bus_url: \"" + vehicle_url + "\"\ntspi:\n  rate_hz: 10\nnmea:\n  serial: " +
                                          pty.slave_path() + "\n  rate_hz: 100\n  talker: GN\n");
  test::ChildProcess svc(std::string(LDV_BIN_DIR) + "/tspi_pub", {"--config", cfg});
  Bus vehicle(vehicle_url);
  Bus remote("udpm://239.255.77.1:7668?ttl=1");
  int heartbeats = 0;
  size_t tspi = 0;
  vehicle.subscribe<ldv_lcm::service_status_t>(
      "STATUS_TSPI_PUB", [&](const ldv_lcm::service_status_t&, const std::string&) { ++heartbeats; });
  remote.subscribe<ldv_lcm::tspi_v1_t>("TSPI", [&](const ldv_lcm::tspi_v1_t&, const std::string&) { ++tspi; });
  ASSERT_TRUE(test::spin_until(
      vehicle, [&] { return heartbeats > 0; }, 30.0))
      << "no heartbeat within 30 s";
  const int before = heartbeats;
  ldv_lcm::nav_state_t nav{};
  nav.gps_week = 2300;
  nav.mode = 2;
  nav.lat_deg = 45.0;
  nav.lon_deg = 7.0;
  for (int k = 0; k < 800; ++k) {  // 4 s at 200 Hz, 100 Hz of NMEA (about 40 kB/s) into a pty nobody reads
    nav.seq = k;
    nav.gps_sow_s = 1000.0 + k * 0.005;
    vehicle.publish("NAV", nav);
    vehicle.handle(0);
    remote.handle(0);
    std::this_thread::sleep_for(std::chrono::microseconds(4500));
  }
  test::spin_until(
      remote, [&] { return tspi >= 40; }, 5.0);
  EXPECT_GE(tspi, 40u) << "TSPI stopped while the NMEA reader stalled";
  test::spin_until(
      vehicle, [&] { return heartbeats >= before + 3; }, 5.0);
  EXPECT_GE(heartbeats, before + 3) << "the service froze";
  // What the pty holds now: whole sentences only.
  std::string bytes;
  char buf[4096];
  ::fcntl(pty.master_fd(), F_SETFL, ::fcntl(pty.master_fd(), F_GETFL) | O_NONBLOCK);
  for (ssize_t n; (n = ::read(pty.master_fd(), buf, sizeof buf)) > 0;) bytes.append(buf, static_cast<size_t>(n));
  size_t sentences = 0, bad = 0, gga = 0;
  // The stream read mid-way may end inside an epoch (the rest is still queued for the port): not a cut sentence.
  if (!bytes.empty() && bytes.back() != '\n') bytes.erase(bytes.rfind('\n') + 1);
  std::istringstream lines(bytes);
  for (std::string line; std::getline(lines, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const auto star = line.rfind('*');
    if (line.empty() || line[0] != '$' || star == std::string::npos || star + 3 != line.size()) {
      ++bad;
      continue;
    }
    uint8_t sum = 0;
    for (size_t i = 1; i < star; ++i) sum ^= static_cast<uint8_t>(line[i]);
    char hex[3];
    std::snprintf(hex, sizeof hex, "%02X", sum);
    bad += line.substr(star + 1) != hex;
    ++sentences;
    gga += line.rfind("$GNGGA,", 0) == 0;
  }
  std::printf("[ info ] the stalled reader then read %zu bytes: %zu sentences (%zu GGA), %zu cut or corrupt\n",
              bytes.size(), sentences, gga, bad);
  EXPECT_GT(gga, 0u);
  EXPECT_EQ(bad, 0u);
  svc.signal(SIGTERM);
  EXPECT_EQ(svc.wait_exit(3.0), 0);
}
