#pragma once
// gnss_link's configuration (deploy/config/gnss_link.yaml): where the bytes come from, which
// protocol they carry, the jump gate, and the output channels.
#include <string>

#include "services/gnss_link/gnss_stream_decoder.hpp"
#include "services/input/byte_source_options.hpp"
#include "common/formats/gnss_jump_gate.hpp"

namespace ldv::gnss {

struct GnssLinkOptions {
  std::string bus_url;
  io::ByteSourceOptions input;
  GnssDecoderOptions decoder;
  JumpGateOptions jump_gate;
  double quiet_flush_s = 0.3;    // NMEA: emit the epoch in progress after this long without bytes
  double stale_after_s = 3.0;    // fault bit "stale" when solutions stop for this long
  std::string solution_channel = "GNSS_SOLUTION";
  std::string pps_channel = "GNSS_PPS";
};

// Empty path: the defaults. Throws config::ConfigError (a std::runtime_error) naming the file, the line,
// the key and what was expected; unknown keys are refused with the nearest valid one.
GnssLinkOptions load_gnss_link_options(const std::string& path);

}  // namespace ldv::gnss
