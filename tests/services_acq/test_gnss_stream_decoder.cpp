// The protocol glue of gnss_link: the right framers for the configured protocol, one set of
// counters, UBX preferred over the NMEA a u-blox port also prints.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

#include "services/gnss_link/gnss_stream_decoder.hpp"
#include "tests/services_acq/nmea_text.hpp"

using namespace ldv;
using namespace ldv::gnss;

namespace {
std::span<const std::uint8_t> bytes_of(const std::string& s) {
  return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()};
}

struct Collected {
  std::vector<GnssSolution> solutions;
  std::vector<PpsTimeLabel> labels;
};

GnssStreamDecoder make(LinkProtocol p, Collected& c) {
  GnssDecoderOptions o;
  o.protocol = p;
  return GnssStreamDecoder(o, [&c](const GnssSolution& s) { c.solutions.push_back(s); },
                           [&c](const PpsTimeLabel& l) { c.labels.push_back(l); });
}

std::string three_epochs() {
  std::string text;
  for (int k = 0; k < 3; ++k) {
    test::NmeaEpoch e;
    e.utc_seconds_of_day = 30000 + k;
    e.lat_deg = 45.0 + 1e-6 * k;
    text += test::nmea_epoch_text(e);
  }
  return text;
}

const char* kRtklibLines =
    "%  GPST                  latitude(deg) longitude(deg)  height(m)   Q  ns   sdn(m)   sde(m)   sdu(m)  sdne(m)  sdeu(m)  sdun(m) age(s)  ratio\n"
    "2024/06/24 08:20:00.000   35.134699010  136.977575490   104.8626   1  12   0.0030   0.0020   0.0080  -0.0010   0.0010  -0.0020   1.00   9.9\n"
    "2024/06/24 08:20:01.000   35.134699020  136.977575480   104.8630   1  12   0.0030   0.0020   0.0080  -0.0010   0.0010  -0.0020   1.00  10.5\n";
}  // namespace

TEST(GnssStreamDecoder, GivenNmeaEpochsInSmallChunks_ThenSolutionsAndLastPulseLabels) {
  Collected c;
  auto d = make(LinkProtocol::kNmea, c);
  const std::string text = three_epochs();
  for (std::size_t i = 0; i < text.size(); i += 7) d.feed(bytes_of(text.substr(i, 7)));
  d.flush_epoch();
  ASSERT_EQ(c.solutions.size(), 3u);
  EXPECT_EQ(c.solutions[0].fix.quality, GnssQuality::kFixed);
  EXPECT_NEAR(c.solutions[2].fix.pos.lat_rad * 180 / M_PI, 45.000002, 1e-9);
  // 2024-06-24 08:20:00 UTC + 18 s = GPS week 2320, Monday 08:20:18 = 116418 s
  EXPECT_EQ(c.solutions[0].time.week, 2320);
  EXPECT_NEAR(c.solutions[0].time.sow_s, 116418.0, 1e-6);
  ASSERT_GE(c.labels.size(), 2u);
  EXPECT_EQ(c.labels[0].refers, PpsTimeLabel::Refers::kLastPulse);
  EXPECT_EQ(d.counters().rejected_total(), 0u);
  EXPECT_EQ(d.active(), "nmea");
}

TEST(GnssStreamDecoder, GivenBadChecksumTruncationAndGarbage_ThenCountedAndGoodEpochsStillDecoded) {
  Collected c;
  auto d = make(LinkProtocol::kNmea, c);
  std::string good = three_epochs();
  std::string bad = test::nmea_line("GPGGA,082005.00,4500.0000000,N,00700.0000000,E,4,14,0.8,300.000,M,0.000,M,1.0,0000");
  bad[20] = '9';  // checksum now wrong
  const std::string truncated = "$GPGGA,082006.00,4500.00";
  d.feed(bytes_of(std::string("\x01\x02garbage\xff") + bad + truncated + good));
  d.flush_epoch();
  EXPECT_EQ(c.solutions.size(), 3u);
  EXPECT_EQ(d.counters().bad_checksum, 1u);
  EXPECT_EQ(d.counters().truncated, 1u);
  EXPECT_GT(d.counters().garbage_bytes, 0u);
}

TEST(GnssStreamDecoder, GivenRtklibTextOnAutoProtocol_ThenItLocksToRtklib) {
  Collected c;
  auto d = make(LinkProtocol::kAuto, c);
  d.feed(bytes_of(kRtklibLines));
  EXPECT_EQ(c.solutions.size(), 2u);
  EXPECT_EQ(d.active(), "rtklib");
  EXPECT_NEAR(c.solutions[1].fix.ratio, 10.5, 1e-9);
  EXPECT_EQ(d.counters().rejected_total(), 0u);
  d.feed(bytes_of("this is not a solution line\n"));
  EXPECT_EQ(d.counters().malformed, 1u);
}

TEST(GnssStreamDecoder, GivenNmeaOnAutoProtocol_ThenRtklibParserIsDropped) {
  Collected c;
  auto d = make(LinkProtocol::kAuto, c);
  d.feed(bytes_of(three_epochs()));
  d.flush_epoch();
  EXPECT_EQ(c.solutions.size(), 3u);
  EXPECT_EQ(d.active(), "nmea");
  EXPECT_EQ(d.counters().rejected_total(), 0u);  // the NMEA lines are not RTKLIB errors
}

TEST(GnssStreamDecoder, GivenTheRealUbxWalk_ThenEveryNavPvtOnceAndTheInterleavedNmeaCountedAsDuplicates) {
  std::ifstream in(std::string(LDV_SHARED_DATA_DIR) + "/drives/walk_0827/gnss_1730.ubx", std::ios::binary);
  ASSERT_TRUE(in);
  const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (LinkProtocol p : {LinkProtocol::kUbx, LinkProtocol::kAuto}) {
    Collected c;
    auto d = make(p, c);
    for (std::size_t i = 0; i < bytes.size(); i += 1000)
      d.feed(std::span(bytes).subspan(i, std::min<std::size_t>(1000, bytes.size() - i)));
    d.flush_end_of_input();
    EXPECT_EQ(c.solutions.size(), 536u) << link_protocol_name(p);
    EXPECT_EQ(d.active(), "ubx");
    EXPECT_EQ(d.counters().bad_checksum, 0u);
    std::printf("[ walk via %s ] solutions %zu, labels %zu, NMEA duplicates dropped %llu, bad checksum %llu, "
                "truncated %llu, malformed %llu\n",
                link_protocol_name(p), c.solutions.size(), c.labels.size(),
                static_cast<unsigned long long>(d.counters().duplicates),
                static_cast<unsigned long long>(d.counters().bad_checksum),
                static_cast<unsigned long long>(d.counters().truncated),
                static_cast<unsigned long long>(d.counters().malformed));
    for (std::size_t i = 1; i < c.solutions.size(); ++i)
      ASSERT_GT(c.solutions[i].time.total_seconds(), c.solutions[i - 1].time.total_seconds());
  }
}
