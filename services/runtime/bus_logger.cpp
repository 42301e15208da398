// ldv_logger: records the bus into an LCM log file (the lcm-logger format, read by lcm-logplayer,
// lcm::LogFile, `ldv export`, `ldv nav --lcm-log`). Why not lcm-logger: in LCM 1.3.1 it subscribes
// with LCM's default queue of 30 messages, so a stall of a few tens of milliseconds on a loaded host
// (600 Hz IMU + 600 Hz NAV) loses messages (seen in tests/integration/test_faults.cpp). Here the
// subscription queue is set explicitly (default 200000 messages). It is a service like the others
// (heartbeat STATUS_LOGGER with the events written, sd_notify), with a clean stop on SIGTERM/SIGINT.
#include <csignal>
#include <cstdio>
#include <ctime>

#include <CLI/CLI.hpp>
#include <lcm/lcm-cpp.hpp>

#include "common/bus/bus.hpp"
#include "common/logging.hpp"
#include "services/runtime/service_runtime.hpp"

int main(int argc, char** argv) {
  CLI::App app{"ldv_logger: records LCM bus traffic into an LCM log file with an explicit subscription queue"};
  std::string url, file, channels = ".*";
  int queue = 200000;
  double flush_s = 0.1;
  app.add_option("--lcm-url", url, "LCM URL of the bus");
  app.add_option("-c,--channel", channels, "channel regex");
  app.add_option("--queue", queue, "subscription queue capacity [messages]");
  app.add_option("--flush-interval", flush_s, "flush the file this often [s]");
  app.add_option("file", file, "log file (overwritten)")->required();
  CLI11_PARSE(app, argc, argv);
  ldv::init_logging();
  try {
    ldv::ServiceRuntime rt("logger", url);
    lcm::LogFile log(file, "w");
    if (!log.good()) throw std::runtime_error("cannot open " + file + " for writing");
    int64_t events = 0;
    rt.bus().subscribe_raw(channels, [&](const std::string& channel, const uint8_t* data, int size) {
      lcm::LogEvent e{};
      e.eventnum = events++;
      e.timestamp = static_cast<int64_t>(ldv::host_time_s() * 1e6);
      e.channel = channel;
      e.datalen = size;
      e.data = const_cast<uint8_t*>(data);
      if (log.writeEvent(&e) == 0) ++rt.counters().received;
      else ++rt.counters().dropped;
    }, queue);
    rt.ready();
    double next_flush = ldv::host_time_s() + flush_s;
    while (rt.running()) {
      rt.bus().handle(20);
      if (ldv::host_time_s() >= next_flush) {
        std::fflush(log.getFilePtr());
        next_flush = ldv::host_time_s() + flush_s;
      }
      rt.tick();
    }
    spdlog::info("ldv_logger: stopping ({} events written, {} write errors)", rt.counters().received, rt.counters().dropped);
  } catch (const std::exception& e) {
    spdlog::error("ldv_logger: {}", e.what());
    return 1;
  }
  return 0;
}
