// NMEA 0183: the spec's classic example sentences (with their published checksums), a stream
// with garbage, truncation and bad checksums, and the epoch assembler's quality/std/time mapping.
#include <gtest/gtest.h>

#include <numbers>
#include <string>
#include <vector>

#include "common/formats/nmea_epoch_assembler.hpp"
#include "common/formats/nmea_framer.hpp"
#include "common/formats/nmea_sentences.hpp"

using namespace ldv;
using namespace ldv::gnss;

namespace {
constexpr double kDeg = std::numbers::pi / 180.0;

// The widely published examples; their checksums are part of the examples, not computed here.
const char* kGga = "$GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,*47\r\n";
const char* kRmc = "$GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,230394,003.1,W*6A\r\n";
const char* kVtg = "$GPVTG,054.7,T,034.4,M,005.5,N,010.2,K*48\r\n";
const char* kZda = "$GPZDA,201530.00,04,07,2002,00,00*60\r\n";
const char* kGst = "$GPGST,172814.0,0.006,0.023,0.020,273.6,0.023,0.020,0.031*6A\r\n";

std::string with_checksum(const std::string& body) {
  char hex[4];
  std::snprintf(hex, sizeof hex, "%02X", nmea_checksum(body));
  return "$" + body + "*" + hex + "\r\n";
}

std::vector<std::string> frame_all(const std::string& stream, NmeaFramerCounters* counters = nullptr) {
  std::vector<std::string> out;
  NmeaFramer framer([&](std::string_view s) { out.emplace_back(s); });
  framer.feed(stream);
  if (counters) *counters = framer.counters();
  return out;
}
}  // namespace

TEST(NmeaFramer, GivenSpecExamples_WhenFramed_ThenAllChecksumsVerify) {
  NmeaFramerCounters c;
  const auto s = frame_all(std::string(kGga) + kRmc + kVtg + kZda + kGst, &c);
  ASSERT_EQ(s.size(), 5u);
  EXPECT_EQ(s[0].substr(0, 12), "GPGGA,123519");
  EXPECT_EQ(c.bad_checksum, 0u);
  EXPECT_EQ(c.truncated, 0u);
  EXPECT_EQ(c.garbage_bytes, 0u);
}

TEST(NmeaFramer, GivenGarbageTruncationAndBadChecksums_WhenFramedInOddChunks_ThenGoodSentencesSurviveAndBadOnesAreCounted) {
  std::string bad_checksum = kGga;
  bad_checksum[bad_checksum.find("*47")+2] = '8';  // *48: wrong
  std::string stream;
  stream += "\x01\xff garbage \xb5\x62";   // 13 garbage bytes before the first '$'
  stream += kGga;
  stream += std::string(kRmc).substr(0, 30);  // cut off: the next '$' interrupts it
  stream += kVtg;
  stream += bad_checksum;
  stream += "$GPZDA,201530.00,04,07,2002,00,00*6";  // checksum cut: one hex digit then CR LF
  stream += "\r\n";
  stream += "$GPZDA,201530.00,04,07,2002,00,00\r\n";  // no checksum at all
  stream += kGst;

  std::vector<std::string> out;
  NmeaFramer framer([&](std::string_view s) { out.emplace_back(s); });
  for (std::size_t i = 0; i < stream.size(); i += 7) framer.feed(std::string_view(stream).substr(i, 7));

  ASSERT_EQ(out.size(), 3u);  // GGA, VTG, GST
  EXPECT_EQ(out[0].substr(0, 5), "GPGGA");
  EXPECT_EQ(out[1].substr(0, 5), "GPVTG");
  EXPECT_EQ(out[2].substr(0, 5), "GPGST");
  EXPECT_EQ(framer.counters().sentences, 3u);
  EXPECT_EQ(framer.counters().bad_checksum, 1u);
  EXPECT_EQ(framer.counters().truncated, 3u);  // cut RMC, cut checksum, missing checksum
  EXPECT_EQ(framer.counters().garbage_bytes, 13u);
}

TEST(NmeaFramer, GivenAnOverlongLine_ThenItIsDroppedAndTheNextSentenceIsKept) {
  NmeaFramerCounters c;
  const auto s = frame_all("$GPTXT," + std::string(500, 'A') + "*00\r\n" + kGga, &c);
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(c.overlong, 1u);
}

TEST(NmeaSentences, GivenTheSpecGga_ThenFieldsAreDecodedInSiUnits) {
  const auto g = parse_gga(frame_all(kGga).at(0));
  ASSERT_TRUE(g);
  EXPECT_DOUBLE_EQ(g->utc_seconds_of_day, 12 * 3600 + 35 * 60 + 19);
  EXPECT_NEAR(g->lat_rad, (48 + 7.038 / 60) * kDeg, 1e-12);
  EXPECT_NEAR(g->lon_rad, (11 + 31.000 / 60) * kDeg, 1e-12);
  EXPECT_EQ(g->quality_code, 1);
  EXPECT_EQ(g->num_sats, 8);
  EXPECT_DOUBLE_EQ(g->hdop, 0.9);
  EXPECT_DOUBLE_EQ(g->altitude_msl_m, 545.4);
  EXPECT_DOUBLE_EQ(g->ellipsoid_height_m(), 545.4 + 46.9);
  EXPECT_FALSE(g->correction_age_s);
}

TEST(NmeaSentences, GivenSouthWestHemispheres_ThenAnglesAreNegative) {
  const auto g = parse_gga("GNGGA,000001.00,3345.000,S,07030.000,W,4,20,0.5,10.0,M,0.0,M,1.2,0001");
  ASSERT_TRUE(g);
  EXPECT_NEAR(g->lat_rad, -33.75 * kDeg, 1e-12);
  EXPECT_NEAR(g->lon_rad, -70.5 * kDeg, 1e-12);
  EXPECT_DOUBLE_EQ(*g->correction_age_s, 1.2);
}

TEST(NmeaSentences, GivenTheSpecRmcVtgZdaGst_ThenFieldsAreDecoded) {
  const auto r = parse_rmc(frame_all(kRmc).at(0));
  ASSERT_TRUE(r);
  EXPECT_TRUE(r->valid);
  EXPECT_EQ(r->date.year, 1994);
  EXPECT_EQ(r->date.month, 3);
  EXPECT_EQ(r->date.day, 23);
  EXPECT_NEAR(r->speed_mps, 22.4 * 1852.0 / 3600.0, 1e-12);
  EXPECT_NEAR(*r->course_true_rad, 84.4 * kDeg, 1e-12);

  const auto v = parse_vtg(frame_all(kVtg).at(0));
  ASSERT_TRUE(v);
  EXPECT_NEAR(*v->course_true_rad, 54.7 * kDeg, 1e-12);
  EXPECT_NEAR(v->speed_mps, 10.2 / 3.6, 1e-12);

  const auto z = parse_zda(frame_all(kZda).at(0));
  ASSERT_TRUE(z);
  EXPECT_DOUBLE_EQ(z->utc_seconds_of_day, 20 * 3600 + 15 * 60 + 30);
  EXPECT_EQ(z->date.year, 2002);
  EXPECT_EQ(z->date.month, 7);
  EXPECT_EQ(z->date.day, 4);

  const auto s = parse_gst(frame_all(kGst).at(0));
  ASSERT_TRUE(s);
  EXPECT_DOUBLE_EQ(s->lat_std_m, 0.023);
  EXPECT_DOUBLE_EQ(s->lon_std_m, 0.020);
  EXPECT_DOUBLE_EQ(s->alt_std_m, 0.031);
  EXPECT_NEAR(s->semi_major_orientation_rad, 273.6 * kDeg, 1e-12);
}

TEST(NmeaSentences, GivenMalformedFields_ThenParsersRefuse) {
  EXPECT_FALSE(parse_gga("GPGGA,123519,4807.038,N,01131.000"));                 // too few fields
  EXPECT_FALSE(parse_gga("GPGGA,12x519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,"));
  EXPECT_FALSE(parse_gga("GPGGA,123519,4867.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,"));  // 67 minutes
  EXPECT_FALSE(parse_gga("GPGGA,123519,4807.038,X,01131.000,E,1,08,0.9,545.4,M,46.9,M,,"));
  EXPECT_FALSE(parse_rmc("GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,231394,003.1,W"));  // month 13
  EXPECT_FALSE(parse_zda("GPZDA,201530.00,04,07"));
  EXPECT_FALSE(parse_gga(frame_all(kRmc).at(0)));  // wrong type
}

TEST(NmeaEpochAssembler, GivenGgaQualityCodes_ThenTheyMapToGnssQuality) {
  EXPECT_EQ(quality_from_gga(4), GnssQuality::kFixed);
  EXPECT_EQ(quality_from_gga(5), GnssQuality::kFloat);
  EXPECT_EQ(quality_from_gga(2), GnssQuality::kDgps);
  EXPECT_EQ(quality_from_gga(1), GnssQuality::kSingle);
  EXPECT_FALSE(quality_from_gga(0));
  EXPECT_FALSE(quality_from_gga(6));  // dead reckoning is not a GNSS measurement
}

TEST(NmeaEpochAssembler, GivenAnRtkReceiverCycle_ThenOneSolutionPerEpochWithGstStdAndGpsTime) {
  std::vector<GnssSolution> sols;
  std::vector<PpsTimeLabel> labels;
  NmeaEpochAssembler assembler([&](const GnssSolution& s) { sols.push_back(s); },
                               [&](const PpsTimeLabel& l) { labels.push_back(l); });
  NmeaFramer framer([&](std::string_view s) { assembler.on_sentence(s); });
  // Two receiver cycles RMC, VTG, GGA, GST, ZDA at 2024-06-24 08:19:42 and :43 UTC (GPS 08:20:00).
  for (int sec : {42, 43}) {
    const std::string t = "0819" + std::to_string(sec) + ".00";
    framer.feed(with_checksum("GNRMC," + t + ",A,3508.0819,N,13658.6545,E,0.0,90.0,240624,,,R"));
    framer.feed(with_checksum("GNVTG,90.0,T,,M,1.944,N,3.6,K,R"));
    framer.feed(with_checksum("GNGGA," + t + ",3508.0819,N,13658.6545,E," + (sec == 42 ? "4" : "5") +
                              ",24,0.6,66.0,M,38.8,M,1.0,0001"));
    framer.feed(with_checksum("GNGST," + t + ",0.5,0.03,0.02,0.0,0.03,0.02,0.05"));
    framer.feed(with_checksum("GNZDA," + t + ",24,06,2024,00,00"));
    framer.feed(with_checksum("GNGSV,1,1,00"));
  }
  assembler.flush();
  ASSERT_EQ(sols.size(), 2u);
  const GnssSolution& s = sols[0];
  EXPECT_EQ(s.fix.quality, GnssQuality::kFixed);
  EXPECT_EQ(sols[1].fix.quality, GnssQuality::kFloat);
  // 2024-06-24 08:19:42 UTC + 18 s = GPST 08:20:00 = week 2320, 116400 s (RTKLIB's header of that day).
  EXPECT_EQ(s.time.week, 2320);
  EXPECT_NEAR(s.time.sow_s, 116400.0, 1e-9);
  EXPECT_NEAR(sols[1].time.sow_s, 116401.0, 1e-9);
  EXPECT_DOUBLE_EQ(s.fix.t_s, s.time.sow_s);
  EXPECT_NEAR(s.fix.pos.h_m, 66.0 + 38.8, 1e-9);
  EXPECT_NEAR(s.fix.pos_std_ned_m.x(), 0.03, 1e-12);
  EXPECT_NEAR(s.fix.pos_std_ned_m.y(), 0.02, 1e-12);
  EXPECT_NEAR(s.fix.pos_std_ned_m.z(), 0.05, 1e-12);
  EXPECT_EQ(s.fix.num_sats, 24);
  EXPECT_DOUBLE_EQ(s.fix.age_s, 1.0);
  ASSERT_TRUE(s.fix.has_velocity);
  EXPECT_NEAR(s.fix.vel_n_mps.y(), 1.0, 1e-3);  // 3.6 km/h due east
  EXPECT_NEAR(s.fix.vel_n_mps.x(), 0.0, 1e-9);
  // Whole-second RMC/ZDA label the pulse that began the second (one label per second).
  ASSERT_EQ(labels.size(), 2u);
  EXPECT_EQ(labels[0].refers, PpsTimeLabel::Refers::kLastPulse);
  EXPECT_NEAR(labels[0].pulse_time.sow_s, 116400.0, 1e-9);
  EXPECT_EQ(assembler.counters().ignored, 2u);  // the GSVs
}

TEST(NmeaEpochAssembler, GivenGgaWithoutFixOrBeforeAnyDate_ThenNoSolutionAndTheReasonIsCounted) {
  std::vector<GnssSolution> sols;
  NmeaEpochAssembler assembler([&](const GnssSolution& s) { sols.push_back(s); });
  assembler.on_sentence("GPGGA,000000.00,,,,,0,00,99.9,,,,,,");
  assembler.on_sentence("GPGGA,000001.00,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,");  // no date yet
  assembler.flush();
  EXPECT_TRUE(sols.empty());
  EXPECT_EQ(assembler.counters().epochs_without_fix, 1u);
  EXPECT_EQ(assembler.counters().epochs_without_date, 1u);
}

// Issue 35, item 12: a date that does not exist (31 February 2024) was published as GPS week 2304.
TEST(NmeaSentences, GivenADayTheCalendarDoesNotHave_ThenRmcAndZdaAreRefused_AndA29FebruaryOfALeapYearIsKept) {
  EXPECT_FALSE(parse_rmc("GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,310224,003.1,W"));
  EXPECT_FALSE(parse_zda("GPZDA,201530.00,31,02,2024,00,00"));
  EXPECT_FALSE(parse_zda("GPZDA,201530.00,29,02,2023,00,00"));  // 2023 is not a leap year
  EXPECT_FALSE(parse_zda("GPZDA,201530.00,31,04,2024,00,00"));  // April has 30 days
  EXPECT_FALSE(parse_zda("GPZDA,201530.00,29,02,2100,00,00"));  // a century, not divisible by 400
  const auto leap = parse_zda("GPZDA,201530.00,29,02,2024,00,00");
  ASSERT_TRUE(leap);
  EXPECT_EQ(leap->date.day, 29);
  EXPECT_TRUE(parse_zda("GPZDA,201530.00,29,02,2000,00,00"));
  EXPECT_TRUE(parse_rmc("GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,290224,003.1,W"));
}
