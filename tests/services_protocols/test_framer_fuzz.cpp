// Malformed input never crashes: bounded random byte streams (pure noise, and noise spliced into
// valid traffic) through every framer and decoder, in random chunk sizes. Run under the default
// build; valgrind/ASan builds of this test catch memory errors the assertions cannot.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "common/formats/nmea_epoch_assembler.hpp"
#include "common/formats/nmea_framer.hpp"
#include "common/formats/rtklib_solution_stream.hpp"
#include "common/formats/ubx_framer.hpp"
#include "common/formats/ubx_messages.hpp"

using namespace ldv::gnss;

namespace {
// Valid traffic of all three protocols, to splice noise into.
std::vector<std::uint8_t> valid_traffic() {
  std::string text =
      "$GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,*47\r\n"
      "$GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,230394,003.1,W*6A\r\n"
      "$GPVTG,054.7,T,034.4,M,005.5,N,010.2,K*48\r\n"
      "$GPZDA,201530.00,04,07,2002,00,00*60\r\n"
      "$GPGST,172814.0,0.006,0.023,0.020,273.6,0.023,0.020,0.031*6A\r\n"
      "2024/06/24 08:20:00.000   35.134699010  136.977575490   104.8626   1  42   0.0024   0.0024   0.0069   0.0008  "
      "-0.0013  -0.0024   0.00   12.0\n";
  std::vector<std::uint8_t> out(text.begin(), text.end());
  std::vector<std::uint8_t> pvt(kUbxNavPvtBytes, 0x11), tp(kUbxTimTpBytes, 0x22);
  for (const auto& f : {ubx_encode(kUbxClassNav, kUbxIdNavPvt, pvt), ubx_encode(kUbxClassTim, kUbxIdTimTp, tp)}) {
    out.insert(out.end(), f.begin(), f.end());
  }
  return out;
}
}  // namespace

TEST(FramerFuzz, GivenRandomAndCorruptedBytes_ThenEveryFramerAndDecoderSurvivesAndCounts) {
  std::mt19937 rng(2024);
  const auto valid = valid_traffic();
  std::uint64_t delivered = 0;

  NmeaEpochAssembler assembler([&](const GnssSolution&) { ++delivered; }, [&](const PpsTimeLabel&) {});
  NmeaFramer nmea([&](std::string_view s) {
    assembler.on_sentence(s);
    parse_gga(s), parse_gst(s), parse_rmc(s), parse_vtg(s), parse_zda(s);
  });
  UbxFramer ubx([&](const UbxFrame& f) {
    if (const auto p = decode_nav_pvt(f.payload)) solution_from_nav_pvt(*p);
    if (const auto t = decode_tim_tp(f.payload)) label_from_tim_tp(*t);
    ++delivered;
  });
  RtklibSolutionStream rtk([&](const GnssSolution&) { ++delivered; });

  std::uniform_int_distribution<int> byte(0, 255), chunk(1, 700), mode(0, 3);
  std::vector<std::uint8_t> buf;
  for (int round = 0; round < 3000; ++round) {  // ~3 MB in total: a few seconds
    buf.clear();
    const int m = mode(rng);
    if (m == 0) {  // pure noise
      for (int i = chunk(rng); i > 0; --i) buf.push_back(static_cast<std::uint8_t>(byte(rng)));
    } else {       // valid traffic with random bytes overwritten, dropped or inserted
      buf = valid;
      for (int i = 0; i < 1 + m * 3; ++i) {
        const std::size_t at = static_cast<std::size_t>(rng() % buf.size());
        if (i % 3 == 0) buf[at] = static_cast<std::uint8_t>(byte(rng));
        else if (i % 3 == 1) buf.erase(buf.begin() + static_cast<std::ptrdiff_t>(at));
        else buf.insert(buf.begin() + static_cast<std::ptrdiff_t>(at), static_cast<std::uint8_t>(byte(rng)));
      }
    }
    for (std::size_t i = 0; i < buf.size();) {
      const std::size_t n = std::min<std::size_t>(static_cast<std::size_t>(chunk(rng)), buf.size() - i);
      const std::span<const std::uint8_t> part(buf.data() + i, n);
      nmea.feed(part);
      ubx.feed(part);
      rtk.feed(part);
      i += n;
    }
  }
  assembler.flush();
  rtk.flush();
  // Still framing after all that: a clean copy goes through.
  const auto before = ubx.counters().frames;
  ubx.feed(valid);
  EXPECT_EQ(ubx.counters().frames, before + 2);
  std::printf("[ fuzz ] NMEA ok %llu bad-checksum %llu truncated %llu | UBX ok %llu bad-checksum %llu overlong %llu | "
              "RTKLIB ok %llu malformed %llu\n",
              (unsigned long long)nmea.counters().sentences, (unsigned long long)nmea.counters().bad_checksum,
              (unsigned long long)nmea.counters().truncated, (unsigned long long)ubx.counters().frames,
              (unsigned long long)ubx.counters().bad_checksum, (unsigned long long)ubx.counters().overlong,
              (unsigned long long)rtk.counters().solutions, (unsigned long long)rtk.counters().malformed_lines);
  EXPECT_GT(nmea.counters().bad_checksum + nmea.counters().truncated, 0u);
  EXPECT_GT(ubx.counters().bad_checksum, 0u);
  EXPECT_GT(rtk.counters().malformed_lines, 0u);
  EXPECT_GT(delivered, 0u);
}
