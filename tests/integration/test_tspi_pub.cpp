// tspi_pub as a real process in a private network namespace: NAV in at 200 Hz on the vehicle bus,
// TSPI out at the configured 10 Hz on its own multicast group, no gaps, clean exit on SIGTERM.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <ldv_lcm/nav_state_t.hpp>
#include <ldv_lcm/service_status_t.hpp>
#include <ldv_lcm/tspi_v1_t.hpp>

#include "common/bus/bus.hpp"
#include "tests/integration/bus_spin.hpp"
#include "tests/integration/child_process.hpp"

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
