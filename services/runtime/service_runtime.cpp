#include "services/runtime/service_runtime.hpp"

#include <csignal>
#include <ctime>
#include <cstdlib>

#include <ldv_lcm/service_status_t.hpp>
#include <systemd/sd-daemon.h>

#include "common/logging.hpp"

namespace ldv {
namespace {
std::atomic<bool> g_stop_requested{false};
extern "C" void on_stop_signal(int) { g_stop_requested = true; }
}  // namespace

double host_time_s() {
  timespec ts{};
  clock_gettime(CLOCK_REALTIME, &ts);
  return ts.tv_sec + ts.tv_nsec * 1e-9;
}

double process_cpu_s() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return ts.tv_sec + ts.tv_nsec * 1e-9;
}

ServiceRuntime::ServiceRuntime(std::string name, const std::string& bus_url)
    : name_(std::move(name)), bus_(bus_url) {
  struct sigaction sa{};
  sa.sa_handler = on_stop_signal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGTERM, &sa, nullptr);
  sigaction(SIGINT, &sa, nullptr);
  std::signal(SIGPIPE, SIG_IGN);  // a vanished TCP/pty peer must not kill the service
  uint64_t watchdog_usec = 0;
  if (sd_watchdog_enabled(0, &watchdog_usec) > 0) watchdog_interval_s_ = watchdog_usec * 1e-6 / 2.0;
}

void ServiceRuntime::ready() {
  state_ = counters_.fault_bits ? 2 : 1;
  sd_notify(0, "READY=1");
  spdlog::info("{}: ready", name_);
  next_heartbeat_s_ = 0.0;
  tick();
}

bool ServiceRuntime::running() const { return !g_stop_requested.load(); }

void ServiceRuntime::tick() {
  const double now = host_time_s();
  if (now >= next_heartbeat_s_) {
    publish_heartbeat();
    next_heartbeat_s_ = now + 1.0;
  }
  if (watchdog_interval_s_ > 0 && now >= next_watchdog_s_) {
    sd_notify(0, "WATCHDOG=1");
    next_watchdog_s_ = now + watchdog_interval_s_;
  }
}

void ServiceRuntime::publish_heartbeat() {
  ldv_lcm::service_status_t m{};
  m.seq = heartbeat_seq_++;
  m.host_time_s = host_time_s();
  m.name = name_;
  m.state = static_cast<int8_t>(running() ? state_ : 3);
  m.received = counters_.received;
  m.dropped = counters_.dropped;
  m.malformed = counters_.malformed + bus_.malformed();
  m.fault_bits = counters_.fault_bits;
  m.cpu_s = process_cpu_s();
  std::string channel = "STATUS_" + name_;
  for (auto& c : channel) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  bus_.publish(channel, m);
}

}  // namespace ldv
