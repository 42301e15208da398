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
