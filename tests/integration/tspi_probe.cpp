// tspi_probe: the two ends of the remote-subscriber test (test_tspi_veth.sh).
//   tspi_probe nav URL RATE_HZ DURATION_S      publishes a plausible nav_state_t on NAV (what fusion does)
//   tspi_probe count URL DURATION_S [CHANNEL]  counts tspi_v1_t on CHANNEL (default TSPI) and prints
//                                              "received N gaps G resets R" (exit 0)
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>

#include <ldv_lcm/nav_state_t.hpp>
#include <ldv_lcm/tspi_v1_t.hpp>

#include "common/bus/bus.hpp"

namespace {
int usage() {
  std::fprintf(stderr, "usage: tspi_probe nav URL RATE_HZ DURATION_S | tspi_probe count URL DURATION_S [CHANNEL]\n");
  return 2;
}
}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) return usage();
  const std::string mode = argv[1], url = argv[2];
  try {
    ldv::Bus bus(url);
    if (mode == "nav" && argc == 5) {
      const double rate_hz = std::atof(argv[3]), duration_s = std::atof(argv[4]);
      const auto t0 = std::chrono::steady_clock::now();
      for (int64_t k = 0; k < static_cast<int64_t>(rate_hz * duration_s); ++k) {
        std::this_thread::sleep_until(t0 + std::chrono::duration<double>(k / rate_hz));
        ldv_lcm::nav_state_t m{};
        m.seq = k;
        m.gps_week = 2300;
        m.gps_sow_s = 345600.0 + k / rate_hz;
        m.lat_deg = 32.8801 + 1e-7 * k;
        m.lon_deg = -117.2340;
        m.height_m = 100.0;
        m.vel_ned_mps[0] = 1.0;
        m.mode = 2;
        bus.publish("NAV", m);
      }
      return 0;
    }
    if (mode == "count" && (argc == 4 || argc == 5)) {
      const double duration_s = std::atof(argv[3]);
      const std::string channel = argc == 5 ? argv[4] : "TSPI";
      ldv::SequenceTracker seq;
      bus.subscribe<ldv_lcm::tspi_v1_t>(channel, [&](const ldv_lcm::tspi_v1_t& t, const std::string&) { seq.observe(t.seq); }, 5000);
      const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(duration_s);
      while (std::chrono::steady_clock::now() < end) bus.handle(20);
      std::printf("received %lld gaps %lld resets %lld malformed %lld\n", static_cast<long long>(seq.received()),
                  static_cast<long long>(seq.lost()), static_cast<long long>(seq.resets()),
                  static_cast<long long>(bus.malformed()));
      return 0;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tspi_probe: %s\n", e.what());
    return 1;
  }
  return usage();
}
