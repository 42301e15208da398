// ldv_bus_bench: the vehicle bus under load (issue 4 benchmarks), run by scripts/bench_bus.sh inside
// a private network namespace (loopback multicast). Not a timed test: it prints numbers.
//  - latency: this process publishes a simulated vehicle's IMU samples (600 Hz) and GNSS solutions
//    (20 Hz, 50 ms late) on the vehicle bus as imu_acq/gnss_link would, stamping host_time_s at
//    publish; the real fusion and tspi_pub run; the NAV and TSPI that carry each sample's epoch are
//    timed on arrival in this process (same CLOCK_REALTIME): IMU in -> NAV out, IMU in -> TSPI out;
//  - loss: per-publisher sequence gaps on NAV and TSPI, every IMU sample turned into a NAV, fusion's
//    and tspi_pub's dropped counters; ldv_logger records the bus as deployed (with rotation);
//  - the device side at the same rates on a second bus: `ldv drive` writes the simulated IMU
//    time-stamp unit (600 Hz) and NMEA receiver (20 Hz) into ptys, imu_acq and gnss_link decode them:
//    their IMU/GNSS_SOLUTION sequence gaps and frame counts;
//  - CPU of each service from its heartbeats' cpu_s (the logger's too).
// With --units DIR the services run with the scheduling their unit files ship (CPUSchedulingPolicy/
// Priority, Nice), applied by chrt/nice before exec as systemd applies it before exec, so every thread
// inherits it; the IMU publisher stands in for imu_acq and takes its scheduling, and the receiver that
// times NAV/TSPI (the measuring instrument) runs above every service, so it measures them, not itself.
// fusion starts from a warm-start state file written from the simulator's truth, so it navigates from
// the first GNSS fix instead of aligning.
#include <pthread.h>
#include <sched.h>
#include <sys/resource.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>
#include <sstream>
#include <thread>

#include <CLI/CLI.hpp>
#include <ldv_lcm/gnss_solution_t.hpp>
#include <ldv_lcm/imu_sample_t.hpp>
#include <ldv_lcm/nav_state_t.hpp>
#include <ldv_lcm/service_status_t.hpp>
#include <ldv_lcm/tspi_v1_t.hpp>

#include "common/bus/bus.hpp"
#include "common/bus/message_conversions.hpp"
#include "common/formats/kfgins_files.hpp"
#include "services/fusion/warm_start.hpp"
#include "services/runtime/service_runtime.hpp"
#include "sim/simulator.hpp"
#include "tests/integration/vehicle_rig.hpp"

using namespace ldv;
namespace fs = std::filesystem;

namespace {
struct Percentiles {
  size_t n = 0;
  double p50 = NAN, p90 = NAN, p99 = NAN, p999 = NAN, max = NAN;
};
Percentiles percentiles(std::vector<double> v) {
  Percentiles p;
  p.n = v.size();
  if (v.empty()) return p;
  std::sort(v.begin(), v.end());
  auto q = [&](double f) { return v[std::min(v.size() - 1, static_cast<size_t>(f * (v.size() - 1) + 0.5))]; };
  p.p50 = q(0.5), p.p90 = q(0.9), p.p99 = q(0.99), p.p999 = q(0.999), p.max = v.back();
  return p;
}
void print_latency(const char* what, const Percentiles& p) {
  std::printf("%-22s n %8zu  p50 %7.3f ms  p90 %7.3f ms  p99 %7.3f ms  p99.9 %7.3f ms  max %8.3f ms\n", what, p.n,
              p.p50 * 1e3, p.p90 * 1e3, p.p99 * 1e3, p.p999 * 1e3, p.max * 1e3);
}
// What a unit file ships for scheduling (systemd.exec CPUSchedulingPolicy=, CPUSchedulingPriority=, Nice=).
struct UnitSched {
  std::string policy = "other";
  int priority = 0;
  int nice = 0;
};
UnitSched unit_sched(const fs::path& unit_file) {
  std::ifstream in(unit_file);
  if (!in) throw std::runtime_error("cannot read " + unit_file.string());
  UnitSched s;
  for (std::string line; std::getline(in, line);) {
    const size_t eq = line.find('=');
    if (line.empty() || line[0] == '#' || eq == std::string::npos) continue;
    const std::string key = line.substr(0, eq), value = line.substr(eq + 1);
    if (key == "CPUSchedulingPolicy") s.policy = value;
    else if (key == "CPUSchedulingPriority") s.priority = std::stoi(value);
    else if (key == "Nice") s.nice = std::stoi(value);
  }
  if (s.policy != "other" && s.policy != "fifo" && s.policy != "rr") throw std::runtime_error(unit_file.string() + ": policy " + s.policy);
  return s;
}
// The command that starts `program` with `s` applied before exec (always set: a child inherits the
// real-time policy of the bench's receiver thread otherwise).
std::vector<std::string> with_sched(const UnitSched& s, const std::string& program, std::vector<std::string> args) {
  std::vector<std::string> cmd;
  if (s.policy == "fifo" || s.policy == "rr") cmd = {"/usr/bin/chrt", s.policy == "fifo" ? "--fifo" : "--rr", std::to_string(s.priority)};
  else cmd = {"/usr/bin/chrt", "--other", "0", "/usr/bin/nice", "-n", std::to_string(s.nice)};
  cmd.push_back(program);
  cmd.insert(cmd.end(), args.begin(), args.end());
  return cmd;
}
void set_thread_sched(const UnitSched& s, const char* who) {
  if (s.policy == "other") return;
  sched_param p{};
  p.sched_priority = s.priority;
  const int rc = pthread_setschedparam(pthread_self(), s.policy == "fifo" ? SCHED_FIFO : SCHED_RR, &p);
  if (rc != 0) throw std::runtime_error(std::string("cannot set real-time scheduling for the ") + who + ": " + std::strerror(rc) +
                                        " (needs root outside a user namespace: tests/integration/netns_run.sh)");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"ldv_bus_bench: IMU-in -> NAV/TSPI-out latency, loss and CPU of the services on the bus"};
  double duration_s = 30, imu_rate_hz = 600, gnss_rate_hz = 20, tspi_rate_hz = 50, gnss_latency_s = 0.05;
  std::string bin_dir = LDV_BIN_DIR, out_dir = "/tmp/ldv_bus_bench", units_dir;
  bool devices = true, logger_on = true;
  app.add_option("--duration", duration_s, "seconds of data");
  app.add_option("--imu-rate", imu_rate_hz, "IMU rate [Hz]");
  app.add_option("--gnss-rate", gnss_rate_hz, "GNSS rate [Hz]");
  app.add_option("--tspi-rate", tspi_rate_hz, "TSPI rate [Hz]");
  app.add_option("--gnss-latency", gnss_latency_s, "GNSS solution latency [s]");
  app.add_option("--bin", bin_dir, "directory of the service binaries");
  app.add_option("--out", out_dir, "work directory (simulation, configs, logs)");
  app.add_flag("!--no-devices", devices, "skip the device side (ldv drive + imu_acq + gnss_link)");
  app.add_flag("!--no-logger", logger_on, "no ldv_logger on the vehicle bus");
  app.add_option("--units", units_dir, "run the services with the scheduling of the unit files in this directory (deploy/systemd)");
  CLI11_PARSE(app, argc, argv);

  const std::string bus_url = "udpm://239.255.76.67:7667?ttl=0";
  const std::string tspi_url = "udpm://239.255.77.1:7668?ttl=0";
  const std::string dev_url = "udpm://239.255.76.68:7669?ttl=0";  // the device side, apart from the latency loop
  fs::remove_all(out_dir);
  fs::create_directories(out_dir);
  const fs::path dir(out_dir);

  // The simulated vehicle: hg1700-typical, 600 Hz IMU, 20 Hz RTK with velocity.
  sim::SimRequest req;
  req.grade = "hg1700-typical";
  req.seed = 3;
  req.duration_s = duration_s + 3.0;
  req.scenario = "figure8";
  req.imu_rate_hz = imu_rate_hz;
  req.gnss_rate_hz = gnss_rate_hz;
  req.gnss_velocity = true;
  std::fprintf(stderr, "simulating %.0f s at %.0f Hz IMU / %.0f Hz GNSS...\n", req.duration_s, imu_rate_hz, gnss_rate_hz);
  sim::SimResult sim = sim::simulate(req);
  sim::write_outputs(sim, (dir / "sim").string());
  const auto imu = sim.imu;
  const auto gnss = sim.gnss;
  const int week = req.gps_week;
  const auto truth0 = read_nav((dir / "sim" / "truth.nav").string()).front();

  // fusion's warm start: the true initial attitude and velocity, "saved" just now.
  WarmState ws;
  ws.saved_host_time_s = host_time_s();
  ws.state.t_s = truth0.sow_s;
  ws.state.pos = truth0.pos;
  ws.state.v_n_mps = truth0.vel_n_mps;
  ws.state.q_b_n = quat_from_euler(truth0.rpy_rad);
  ws.std.att_rad = Vec3::Constant(0.05 * kDegToRad);
  const std::string state_file = (dir / "fusion_state.yaml").string();
  save_warm_state(state_file, ws);
  std::ofstream(dir / "fusion.yaml") << "bus_url: \"" << bus_url << "\"\nkfgins_config: " << (dir / "sim" / "kfgins.yaml").string()
                                     << "\nhistory_s: 3.0\nstate_file: " << state_file << "\nwarm_start_max_age_s: 120\n";
  std::ofstream(dir / "tspi_pub.yaml") << "bus_url: \"" << bus_url << "\"\ntspi: {rate_hz: " << tspi_rate_hz
                                       << ", group: 239.255.77.1, port: 7668, ttl: 0}\n";
  std::ofstream(dir / "imu_acq.yaml") << "bus_url: \"" << dev_url << "\"\ninput: {type: serial, serial: {device: " << (dir / "imu_tty").string()
                                      << ", baud: 921600}}\nprotocol: tsu\ntsu: {counter_hz: 10.0e6}\nsample_rate_hz: " << imu_rate_hz
                                      << "\npps: {source: device, label_refers: auto}\n";
  std::ofstream(dir / "gnss_link.yaml") << "bus_url: \"" << dev_url << "\"\ninput: {type: serial, serial: {device: " << (dir / "gnss_tty").string()
                                        << ", baud: 115200}}\nprotocol: nmea\ngps_minus_utc_s: 18\n";

  std::map<std::string, UnitSched> sched;  // by service name; empty without --units
  if (!units_dir.empty()) {
    for (const char* name : {"imu_acq", "gnss_link", "fusion", "tspi_pub", "logger"}) {
      std::string unit = std::string("ldvnav-") + name + ".service";
      std::replace(unit.begin(), unit.end(), '_', '-');
      sched[std::string(name) == "logger" ? "ldv_logger" : name] = unit_sched(fs::path(units_dir) / unit);
    }
    for (const auto& [name, s] : sched)
      std::fprintf(stderr, "scheduling from %s: %-9s %s %d, nice %d\n", units_dir.c_str(), name.c_str(), s.policy.c_str(), s.priority, s.nice);
  }
  if (!sched.empty()) {
    // The measuring receiver above every service. Before the receivers' buses exist: LCM reads the
    // socket in a thread of its own, which inherits the scheduling of the thread that creates the bus.
    UnitSched rx_sched{"fifo", 0, 0};
    for (const auto& [name, s] : sched) rx_sched.priority = std::max(rx_sched.priority, s.priority + 10);
    set_thread_sched(rx_sched, "receiver");
  }
  // Receivers first, then the services.
  Bus rx(bus_url), rx_tspi(tspi_url), rx_dev(dev_url);
  const size_t n_imu = std::min(imu.size(), static_cast<size_t>(duration_s * imu_rate_hz));
  std::vector<std::atomic<double>> published_at(n_imu);
  for (auto& a : published_at) a = NAN;
  const double t0 = imu.front().t_s;
  auto index_of = [&](double sow) -> long { return std::lround((sow - t0) * imu_rate_hz); };
  std::vector<double> nav_latency, tspi_latency;
  nav_latency.reserve(n_imu);
  SequenceTracker nav_seq, tspi_seq, dev_imu_seq, dev_gnss_seq;
  long nav_unmatched = 0;
  std::map<std::string, std::pair<ldv_lcm::service_status_t, ldv_lcm::service_status_t>> status;  // first, last
  rx.subscribe<ldv_lcm::nav_state_t>("NAV", [&](const ldv_lcm::nav_state_t& m, const std::string&) {
    const double now = host_time_s();
    nav_seq.observe(m.seq);
    const long k = index_of(m.gps_sow_s);
    if (k >= 0 && k < static_cast<long>(n_imu) && std::isfinite(published_at[k].load())) nav_latency.push_back(now - published_at[k]);
    else ++nav_unmatched;
  }, 20000);
  rx_tspi.subscribe<ldv_lcm::tspi_v1_t>("TSPI", [&](const ldv_lcm::tspi_v1_t& m, const std::string&) {
    const double now = host_time_s();
    tspi_seq.observe(m.seq);
    const long k = index_of(m.gps_sow_s);
    if (k >= 0 && k < static_cast<long>(n_imu) && std::isfinite(published_at[k].load())) tspi_latency.push_back(now - published_at[k]);
  }, 5000);
  auto on_status = [&](const ldv_lcm::service_status_t& m, const std::string& ch) {
    auto it = status.find(ch);
    if (it == status.end()) status.emplace(ch, std::make_pair(m, m));
    else it->second.second = m;
  };
  rx.subscribe<ldv_lcm::service_status_t>("STATUS_.*", on_status, 100);
  rx_dev.subscribe<ldv_lcm::service_status_t>("STATUS_.*", on_status, 100);
  rx_dev.subscribe<ldv_lcm::imu_sample_t>("IMU", [&](const ldv_lcm::imu_sample_t& m, const std::string&) { dev_imu_seq.observe(m.seq); }, 20000);
  rx_dev.subscribe<ldv_lcm::gnss_solution_t>("GNSS_SOLUTION", [&](const ldv_lcm::gnss_solution_t& m, const std::string&) {
    dev_gnss_seq.observe(m.seq);
  }, 1000);

  auto logged = [&](const std::string& name, std::vector<std::string> args) {
    const std::string log = (dir / (name + ".log")).string();
    if (sched.empty()) return test::start_logged(bin_dir + "/" + name, args, log);
    auto cmd = with_sched(sched.count(name) ? sched.at(name) : UnitSched{}, bin_dir + "/" + name, args);
    const std::string program = cmd.front();
    return test::start_logged(program, {cmd.begin() + 1, cmd.end()}, log);
  };
  std::unique_ptr<test::ChildProcess> logger;
  // As deploy/systemd/ldvnav-logger.service records (rotating files), so its cost is the deployed one.
  if (logger_on) logger = logged("ldv_logger", {"--lcm-url", bus_url, "--max-file-mb", "256", "--max-total-mb", "1024", (dir / "bench.lcmlog").string()});
  auto fusion = logged("fusion", {"--config", (dir / "fusion.yaml").string()});
  auto tspi = logged("tspi_pub", {"--config", (dir / "tspi_pub.yaml").string()});
  std::unique_ptr<test::ChildProcess> drive, imu_acq, gnss_link;
  if (devices) {
    drive = logged("ldv", {"drive", (dir / "sim").string(), "--imu-link", (dir / "imu_tty").string(), "--gnss-link",
                           (dir / "gnss_tty").string(), "--start-delay", "1.5"});
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    imu_acq = logged("imu_acq", {"--config", (dir / "imu_acq.yaml").string()});
    gnss_link = logged("gnss_link", {"--config", (dir / "gnss_link.yaml").string()});
  }
  auto spin_all = [&](double s) {
    const double end = test::steady_s() + s;
    while (test::steady_s() < end) {
      pollfd fds[3] = {{rx.fd(), POLLIN, 0}, {rx_tspi.fd(), POLLIN, 0}, {rx_dev.fd(), POLLIN, 0}};
      if (::poll(fds, 3, 5) <= 0) continue;
      if (fds[0].revents & POLLIN) rx.handle(0);
      if (fds[1].revents & POLLIN) rx_tspi.handle(0);
      if (fds[2].revents & POLLIN) rx_dev.handle(0);
    }
  };
  spin_all(1.5);

  // The publisher: IMU at its rate, each GNSS solution gnss_latency_s after its epoch.
  std::atomic<bool> done{false};
  int64_t imu_published = 0, gnss_published = 0;
  std::thread publisher([&] {
    if (!sched.empty()) set_thread_sched(sched.at("imu_acq"), "IMU publisher (imu_acq's stand-in)");
    Bus tx(bus_url);
    const auto wall0 = std::chrono::steady_clock::now();
    auto until = [&](double t) { std::this_thread::sleep_until(wall0 + std::chrono::duration<double>(t - t0)); };
    size_t g = 0;
    while (g < gnss.size() && gnss[g].t_s < t0) ++g;
    for (size_t k = 0; k < n_imu; ++k) {
      while (g < gnss.size() && gnss[g].t_s + gnss_latency_s <= imu[k].t_s) {
        until(gnss[g].t_s + gnss_latency_s);
        auto m = message_from_gnss(gnss[g++], week, gnss_published++);
        m.host_time_s = host_time_s();
        tx.publish("GNSS_SOLUTION", m);
      }
      until(imu[k].t_s);
      auto m = message_from_imu(imu[k], week, imu_published++);
      m.host_time_s = host_time_s();
      published_at[k] = m.host_time_s;
      tx.publish("IMU", m);
    }
    done = true;
  });
  const double start_s = test::steady_s();
  double next_report = start_s + 60;
  while (!done) {
    spin_all(0.2);
    if (test::steady_s() > next_report) {
      std::fprintf(stderr, "  %.0f s: NAV %lld (lost %lld), TSPI %lld (lost %lld), device IMU %lld (lost %lld)\n",
                   test::steady_s() - start_s, static_cast<long long>(nav_seq.received()), static_cast<long long>(nav_seq.lost()),
                   static_cast<long long>(tspi_seq.received()), static_cast<long long>(tspi_seq.lost()),
                   static_cast<long long>(dev_imu_seq.received()), static_cast<long long>(dev_imu_seq.lost()));
      next_report += 60;
    }
  }
  publisher.join();
  spin_all(2.5);  // last messages and heartbeats
  for (auto* p : {fusion.get(), tspi.get(), imu_acq.get(), gnss_link.get()})
    if (p) p->signal(SIGTERM);
  for (auto* p : {fusion.get(), tspi.get(), imu_acq.get(), gnss_link.get()})
    if (p) p->wait_exit(5);
  if (logger) {
    logger->signal(SIGTERM);
    logger->wait_exit(5);
  }
  if (drive) drive->signal(SIGKILL);

  double load[3] = {0, 0, 0};
  getloadavg(load, 3);
  std::printf("== ldv_bus_bench: %.0f s, IMU %.0f Hz, GNSS %.0f Hz (%.0f ms late), TSPI %.0f Hz, logger %s, scheduling %s; load average "
              "%.2f %.2f %.2f on %ld cores\n",
              duration_s, imu_rate_hz, gnss_rate_hz, gnss_latency_s * 1e3, tspi_rate_hz, logger_on ? "on" : "off",
              sched.empty() ? "default (SCHED_OTHER, nice 0)" : ("of the units in " + units_dir).c_str(), load[0], load[1], load[2],
              sysconf(_SC_NPROCESSORS_ONLN));
  print_latency("IMU in -> NAV out", percentiles(nav_latency));
  print_latency("IMU in -> TSPI out", percentiles(tspi_latency));
  const auto f = status.count("STATUS_FUSION") ? status.at("STATUS_FUSION").second : ldv_lcm::service_status_t{};
  const auto t = status.count("STATUS_TSPI_PUB") ? status.at("STATUS_TSPI_PUB").second : ldv_lcm::service_status_t{};
  std::printf("loss: IMU published %lld, GNSS %lld; fusion heartbeat received %lld dropped %lld malformed %lld; NAV received %lld "
              "(publisher gaps %lld, not matched %ld); tspi_pub received %lld dropped %lld; TSPI received %lld (gaps %lld, resets %lld)\n",
              static_cast<long long>(imu_published), static_cast<long long>(gnss_published), static_cast<long long>(f.received),
              static_cast<long long>(f.dropped), static_cast<long long>(f.malformed), static_cast<long long>(nav_seq.received()),
              static_cast<long long>(nav_seq.lost()), nav_unmatched, static_cast<long long>(t.received), static_cast<long long>(t.dropped),
              static_cast<long long>(tspi_seq.received()), static_cast<long long>(tspi_seq.lost()), static_cast<long long>(tspi_seq.resets()));
  if (devices) {
    const auto a = status.count("STATUS_IMU_ACQ") ? status.at("STATUS_IMU_ACQ").second : ldv_lcm::service_status_t{};
    const auto g = status.count("STATUS_GNSS_LINK") ? status.at("STATUS_GNSS_LINK").second : ldv_lcm::service_status_t{};
    std::printf("device side: imu_acq frames %lld, dropped %lld, malformed %lld, IMU received %lld (gaps %lld); gnss_link received %lld "
                "dropped %lld malformed %lld, GNSS_SOLUTION received %lld (gaps %lld)\n",
                static_cast<long long>(a.received), static_cast<long long>(a.dropped), static_cast<long long>(a.malformed),
                static_cast<long long>(dev_imu_seq.received()), static_cast<long long>(dev_imu_seq.lost()), static_cast<long long>(g.received),
                static_cast<long long>(g.dropped), static_cast<long long>(g.malformed), static_cast<long long>(dev_gnss_seq.received()),
                static_cast<long long>(dev_gnss_seq.lost()));
  }
  std::printf("CPU (from the heartbeats' cpu_s, %% of one core over the span of the heartbeats):\n");
  for (const auto& [ch, fl] : status) {
    const double span = fl.second.host_time_s - fl.first.host_time_s;
    if (span <= 0) continue;
    std::printf("  %-18s %7.2f s CPU total, %6.2f %% over %.0f s\n", ch.c_str(), fl.second.cpu_s,
                100.0 * (fl.second.cpu_s - fl.first.cpu_s) / span, span);
  }
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  std::printf("  %-18s %7.2f s CPU (publisher + receivers + simulation)\n", "bench itself",
              ru.ru_utime.tv_sec + ru.ru_stime.tv_sec + 1e-6 * (ru.ru_utime.tv_usec + ru.ru_stime.tv_usec));
  const bool lossless = nav_seq.lost() == 0 && tspi_seq.lost() == 0 && f.dropped == 0 && t.dropped == 0 &&
                        nav_seq.received() >= imu_published - static_cast<int64_t>(imu_rate_hz) && (!devices || dev_imu_seq.lost() == 0);
  std::printf("result: %s\n", lossless ? "no message lost" : "MESSAGES LOST");
  return lossless ? 0 : 3;
}
