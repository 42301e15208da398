// gnss_link's decoder over any bytes (NMEA, UBX and RTKLIB solution lines, the protocol chosen by the first
// byte, chunked by the second): never throws, and every solution it hands out passes gnss::implausibility (what
// the bus-input contract checks again) and every PPS label carries a plausible GPS time.
#include <algorithm>
#include <span>

#include "common/formats/gnss_solution_checks.hpp"
#include "services/gnss_link/gnss_stream_decoder.hpp"
#include "tests/fuzz/fuzz_support.hpp"

using namespace ldv;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 2) return 0;
  using gnss::LinkProtocol;
  gnss::GnssDecoderOptions o;
  constexpr LinkProtocol kProtocols[] = {LinkProtocol::kAuto, LinkProtocol::kNmea, LinkProtocol::kUbx,
                                         LinkProtocol::kRtklib};
  o.protocol = kProtocols[data[0] % 4];
  const size_t chunk = 1 + data[1] % 64;
  gnss::GnssStreamDecoder decoder(
      o, [](const gnss::GnssSolution& s) { fuzz::require(!gnss::implausibility(s), "an implausible solution out"); },
      [](const gnss::PpsTimeLabel& l) { fuzz::require(!gnss::implausibility(l), "an implausible PPS label out"); });
  for (size_t at = 2; at < size; at += chunk)
    decoder.feed(std::span<const uint8_t>(data + at, std::min(chunk, size - at)));
  decoder.flush_epoch();
  decoder.flush_end_of_input();
  return 0;
}
