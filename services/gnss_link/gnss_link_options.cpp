#include "services/gnss_link/gnss_link_options.hpp"

#include "common/config/config_section.hpp"

namespace ldv::gnss {

GnssLinkOptions load_gnss_link_options(const std::string& path) {
  using config::Range;
  GnssLinkOptions o;
  if (path.empty()) return o;
  config::ConfigSection y = config::ConfigSection::load(path);
  o.bus_url = y.text("bus_url", o.bus_url);
  o.input = io::byte_source_options_from(y.section("input"), o.input);
  const std::string name = y.choice("protocol", link_protocol_name(o.decoder.protocol), {"nmea", "rtklib", "ubx", "auto"});
  o.decoder.protocol = *link_protocol_from_name(name);
  // GPS - UTC: 18 s since 2017; never negative, and a leap second is added at most twice a year.
  o.decoder.nmea.gps_minus_utc_s = y.number("gps_minus_utc_s", o.decoder.nmea.gps_minus_utc_s, Range::between(0.0, 60.0));
  o.decoder.rtklib.gps_minus_utc_s = o.decoder.nmea.gps_minus_utc_s;
  config::ConfigSection n = y.section("nmea");
  const std::vector<double> defaults(std::begin(o.decoder.nmea.default_std_m), std::end(o.decoder.nmea.default_std_m));
  // Per quality: fixed float sbas dgps single ppp [m].
  const std::vector<double> stds = n.numbers("default_std_m", defaults, 6, Range::above(0.0).up_to(1000.0));
  for (int i = 0; i < 6; ++i) o.decoder.nmea.default_std_m[i] = stds[i];
  o.decoder.nmea.horizontal_velocity_std_mps =
      n.number("horizontal_velocity_std_mps", o.decoder.nmea.horizontal_velocity_std_mps, Range::above(0.0).up_to(100.0));
  o.quiet_flush_s = n.number("quiet_flush_s", o.quiet_flush_s, Range::above(0.0).up_to(10.0));
  config::ConfigSection g = y.section("jump_gate");
  o.jump_gate.max_jump_m = g.number("max_jump_m", o.jump_gate.max_jump_m, Range::above(0.0));
  o.jump_gate.max_gap_s = g.number("max_gap_s", o.jump_gate.max_gap_s, Range::above(0.0));
  o.jump_gate.rejections_to_reset = static_cast<int>(g.integer("rejections_to_reset", o.jump_gate.rejections_to_reset, 1, 1000));
  o.stale_after_s = y.number("stale_after_s", o.stale_after_s, Range::above(0.0).up_to(3600.0));
  config::ConfigSection c = y.section("channels");
  o.solution_channel = c.channel("solution", o.solution_channel);
  o.pps_channel = c.channel("pps", o.pps_channel);
  y.refuse_unknown();
  return o;
}

}  // namespace ldv::gnss
