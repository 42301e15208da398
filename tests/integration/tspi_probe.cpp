// tspi_probe: the two ends of the remote-subscriber test (test_tspi_veth.sh).
//   tspi_probe nav URL RATE_HZ DURATION_S      publishes a plausible nav_state_t on NAV (what fusion does)
//   tspi_probe count URL MAX_S [CHANNEL [EXPECT]]  counts tspi_v1_t on CHANNEL (default TSPI) until EXPECT
//                                              arrived, SIGTERM/SIGINT, or MAX_S; prints "received N gaps G
//                                              resets R malformed M" (exit 0). "subscribed" on stderr once
//                                              it listens, so a script can wait for it instead of sleeping
//   tspi_probe wait URL CHANNEL MAX_S          exits 0 at the first message on CHANNEL (e.g. a service's
//                                              heartbeat: it is up), 1 after MAX_S
#include <csignal>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>

#include <ldv_lcm/nav_state_t.hpp>
#include <ldv_lcm/tspi_v1_t.hpp>

#include "common/bus/bus.hpp"

namespace {
volatile std::sig_atomic_t g_stop = 0;
extern "C" void on_stop(int) { g_stop = 1; }
int usage() {
  std::fprintf(stderr, "usage: tspi_probe nav URL RATE_HZ DURATION_S | tspi_probe count URL DURATION_S [CHANNEL]\n");
  return 2;
}
}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) return usage();
  std::signal(SIGTERM, on_stop);
  std::signal(SIGINT, on_stop);
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
    if (mode == "count" && argc >= 4 && argc <= 6) {
      const double duration_s = std::atof(argv[3]);
      const std::string channel = argc >= 5 ? argv[4] : "TSPI";
      const long long expect = argc == 6 ? std::atoll(argv[5]) : -1;
      ldv::SequenceTracker seq;
      bus.subscribe<ldv_lcm::tspi_v1_t>(channel, [&](const ldv_lcm::tspi_v1_t& t, const std::string&) { seq.observe(t.seq); }, 5000);
      std::fprintf(stderr, "subscribed\n");
      const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(duration_s);
      while (!g_stop && std::chrono::steady_clock::now() < end && (expect < 0 || seq.received() < expect)) bus.handle(20);
      std::printf("received %lld gaps %lld resets %lld malformed %lld\n", static_cast<long long>(seq.received()),
                  static_cast<long long>(seq.lost()), static_cast<long long>(seq.resets()),
                  static_cast<long long>(bus.malformed()));
      return 0;
    }
    if (mode == "wait" && argc == 5) {
      bool seen = false;
      bus.subscribe_raw(argv[3], [&](const std::string&, const uint8_t*, int) { seen = true; }, 100);
      const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(std::atof(argv[4]));
      while (!seen && !g_stop && std::chrono::steady_clock::now() < end) bus.handle(20);
      if (!seen) std::fprintf(stderr, "tspi_probe: nothing on %s within %s s\n", argv[3], argv[4]);
      return seen ? 0 : 1;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tspi_probe: %s\n", e.what());
    return 1;
  }
  return usage();
}
