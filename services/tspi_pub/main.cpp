// tspi_pub: the remote-facing product. Subscribes NAV on the vehicle bus and publishes TSPI
// (tspi_v1_t) at a configured rate on a configured multicast group with a TTL for the vehicle network.
#include <CLI/CLI.hpp>
#include <memory>

#include "common/config/config_section.hpp"
#include "common/logging.hpp"
#include "services/runtime/service_runtime.hpp"
#include "services/tspi_pub/nmea_output.hpp"
#include "services/tspi_pub/tspi_from_nav.hpp"

namespace {
struct TspiOptions {
  std::string bus_url;             // the vehicle bus (NAV comes from here)
  double rate_hz = 50.0;           // TSPI rate
  std::string group = "239.255.77.1";
  int port = 7668;
  int ttl = 1;                     // >= 1 to leave the host onto the vehicle network
  std::string channel = "TSPI";
  bool print = false;              // also print TSPI lines to stdout (1 Hz)
  ldv::NmeaOutputOptions nmea;     // NMEA 0183 for a downstream device (off unless a serial port or UDP is given)
};

TspiOptions load_options(const std::string& path) {
  using ldv::config::Range;
  TspiOptions o;
  if (path.empty()) return o;
  ldv::config::ConfigSection y = ldv::config::ConfigSection::load(path);
  o.bus_url = y.text("bus_url", o.bus_url);
  ldv::config::ConfigSection t = y.section("tspi");
  o.rate_hz = t.number("rate_hz", o.rate_hz, Range::above(0.0).up_to(1000.0));
  o.group = t.ipv4_multicast_group("group", o.group);
  o.port = static_cast<int>(t.integer("port", o.port, 1, 65535));
  o.ttl = static_cast<int>(t.integer("ttl", o.ttl, 0, 255));
  o.channel = t.channel("channel", o.channel);
  o.print = t.flag("print", o.print);
  o.nmea = ldv::nmea_output_options(y.section("nmea"));
  y.refuse_unknown();
  return o;
}
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"tspi_pub: publishes TSPI (tspi_v1_t) from NAV at a configured rate, multicast group and TTL"};
  std::string config_path, bus_url_override;
  bool print = false;
  app.add_option("-c,--config", config_path, "YAML configuration (deploy/config/tspi_pub.yaml)");
  app.add_option("--bus-url", bus_url_override, "vehicle bus LCM URL (overrides the config)");
  app.add_flag("--print", print, "print one TSPI line per second to stdout");
  CLI11_PARSE(app, argc, argv);
  ldv::init_logging();
  try {
    TspiOptions o = load_options(config_path);
    if (!bus_url_override.empty()) o.bus_url = bus_url_override;
    o.print = o.print || print;
    ldv::ServiceRuntime rt("tspi_pub", o.bus_url);
    const std::string tspi_url = "udpm://" + o.group + ":" + std::to_string(o.port) + "?ttl=" + std::to_string(o.ttl);
    ldv::Bus tspi_bus(tspi_url);
    ldv::TspiDecimator decimator(o.rate_hz);
    // NMEA at its own rate on the same GPS-time grid, from the same NAV
    std::unique_ptr<ldv::NmeaOutput> nmea;
    ldv::TspiDecimator nmea_decimator(o.nmea.rate_hz);
    if (o.nmea.enabled()) nmea = std::make_unique<ldv::NmeaOutput>(o.nmea);
    ldv::SequenceTracker nav_seq;
    double next_print_s = 0;
    rt.bus().subscribe<ldv_lcm::nav_state_t>("NAV", [&](const ldv_lcm::nav_state_t& nav, const std::string&) {
      ++rt.counters().received;
      rt.counters().dropped += nav_seq.observe(nav.seq);
      if (!ldv::TspiDecimator::is_usable(nav)) {
        ++rt.counters().malformed;
        return;
      }
      if (nmea)
        if (auto t = nmea_decimator.on_nav(nav)) nmea->send(*t, ldv::host_time_s());
      if (auto t = decimator.on_nav(nav)) {
        tspi_bus.publish(o.channel, *t);
        const double nav_t_s = nav.gps_week * 604800.0 + nav.gps_sow_s;  // one scale across weeks
        if (o.print && nav_t_s >= next_print_s) {
          std::printf("TSPI week %d sow %.3f lat %.9f lon %.9f h %.3f vN %.3f vE %.3f vD %.3f rpy %.3f %.3f %.3f "
                      "std_h %.3f m q %d\n",
                      t->gps_week, t->gps_sow_s, t->lat_deg, t->lon_deg, t->height_m, t->vel_ned_mps[0],
                      t->vel_ned_mps[1], t->vel_ned_mps[2], t->rpy_deg[0], t->rpy_deg[1], t->rpy_deg[2],
                      std::hypot(t->pos_std_ned_m[0], t->pos_std_ned_m[1]), t->quality);
          std::fflush(stdout);
          next_print_s = std::floor(nav_t_s) + 1.0;
        }
      }
    }, 5000);
    spdlog::info("tspi_pub: NAV from '{}', TSPI on {} channel {} at {} Hz", o.bus_url, tspi_url, o.channel, o.rate_hz);
    if (nmea)
      spdlog::info("tspi_pub: NMEA ({}) at {} Hz{}{}", o.nmea.talker, o.nmea.rate_hz,
                   o.nmea.serial.empty() ? "" : " on serial " + o.nmea.serial,
                   o.nmea.udp.empty() ? "" : " to UDP " + o.nmea.udp);
    rt.ready();
    while (rt.running()) {
      rt.bus().handle(50);
      if (nmea) nmea->maintain(ldv::host_time_s());
      rt.tick();
    }
    spdlog::info("tspi_pub: stopping (received {}, dropped {}, malformed {})", rt.counters().received,
                 rt.counters().dropped, rt.counters().malformed);
    if (nmea)
      spdlog::info("tspi_pub: NMEA epochs sent {}, dropped {} (a reader that stalled or a device that was gone)",
                   nmea->epochs_sent(), nmea->epochs_dropped());
  } catch (const std::exception& e) {
    spdlog::error("tspi_pub: {}", e.what());
    return 1;
  }
  return 0;
}
