#pragma once
// What every ldvnav service shares (DESIGN.md section 1): the bus, a 1 Hz heartbeat on
// STATUS_<NAME> with received/dropped/malformed counters and fault bits, systemd readiness and
// watchdog (sd_notify), and a clean stop on SIGTERM/SIGINT. A service's main loop is:
//   ServiceRuntime rt("tspi_pub", bus_url);  ... subscribe ...;  rt.ready();
//   while (rt.running()) { rt.bus().handle(50); rt.tick(); }
#include <atomic>
#include <cstdint>
#include <string>

#include "common/bus/bus.hpp"

namespace ldv {

struct ServiceCounters {
  int64_t received = 0;
  int64_t dropped = 0;
  int64_t malformed = 0;
  int32_t fault_bits = 0;
};

class ServiceRuntime {
 public:
  ServiceRuntime(std::string name, const std::string& bus_url);
  ServiceRuntime(const ServiceRuntime&) = delete;
  ServiceRuntime& operator=(const ServiceRuntime&) = delete;

  Bus& bus() { return bus_; }
  ServiceCounters& counters() { return counters_; }
  const std::string& name() const { return name_; }

  // Tells systemd the service is ready (Type=notify) and starts the heartbeat: running, or degraded when the
  // fault bits set before it say so (a device that could not be opened).
  void ready();
  // Sends the heartbeat and the watchdog ping when due; call at least every 100 ms.
  void tick();
  // False once SIGTERM/SIGINT arrived.
  bool running() const;
  // state: 0 starting, 1 running, 2 degraded, 3 stopping
  void set_state(int state) { state_ = state; }

 private:
  void publish_heartbeat();

  std::string name_;
  Bus bus_;
  ServiceCounters counters_;
  int state_ = 0;
  int64_t heartbeat_seq_ = 0;
  double next_heartbeat_s_ = 0.0;
  double next_watchdog_s_ = 0.0;
  double watchdog_interval_s_ = 0.0;  // half of WATCHDOG_USEC, 0 if systemd did not ask for pings
};

// Host clock, seconds (CLOCK_REALTIME), and process CPU time.
double host_time_s();
double process_cpu_s();

}  // namespace ldv
