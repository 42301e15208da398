// u-blox UBX: synthetic frames with known fields, resynchronisation, and the real bytes of the
// walk_0827 receiver checked against the RTKLIB .pos of the same walk and against the NMEA the
// receiver interleaved in the same stream.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <map>
#include <numbers>
#include <vector>

#include "common/geo/earth_model.hpp"
#include "common/formats/nmea_epoch_assembler.hpp"
#include "common/formats/nmea_framer.hpp"
#include "common/formats/rtklib_solution.hpp"
#include "common/formats/ubx_framer.hpp"
#include "common/formats/ubx_messages.hpp"

using namespace ldv;
using namespace ldv::gnss;

namespace {
constexpr double kUbxDeg_rad = std::numbers::pi / 180.0;
const std::string kWalk = std::string(LDV_SHARED_DATA_DIR) + "/drives/walk_0827/";

void put(std::vector<std::uint8_t>& p, std::size_t at, std::uint64_t v, int bytes) {
  for (int k = 0; k < bytes; ++k) p[at + k] = static_cast<std::uint8_t>(v >> (8 * k));
}

// A NAV-PVT payload written field by field from the interface description's offsets.
std::vector<std::uint8_t> nav_pvt_payload() {
  std::vector<std::uint8_t> p(kUbxNavPvtBytes, 0);
  put(p, 0, 116400250, 4);  // iTOW: Monday 08:20:00.250 GPST (2024-06-24)
  put(p, 4, 2024, 2);
  p[6] = 6, p[7] = 24, p[8] = 8, p[9] = 19, p[10] = 42;
  p[11] = 0x07;                                   // date, time valid, fully resolved
  put(p, 16, static_cast<std::uint32_t>(249'600'000), 4);  // nano: the exact epoch is .2496
  p[20] = 3;                                      // 3D
  p[21] = 0x01 | 0x02 | (2 << 6);                 // fix ok, differential, carrier fixed
  p[23] = 31;
  put(p, 24, static_cast<std::uint32_t>(1369775755), 4);   // lon 136.9775755 deg
  put(p, 28, static_cast<std::uint32_t>(351346990), 4);    // lat 35.1346990 deg
  put(p, 32, 104862, 4);                          // height 104.862 m
  put(p, 40, 14, 4);                              // hAcc 14 mm
  put(p, 44, 10, 4);                              // vAcc 10 mm
  put(p, 48, static_cast<std::uint32_t>(-1500), 4);  // velN -1.5 m/s
  put(p, 52, 250, 4);
  put(p, 56, 20, 4);
  put(p, 68, 50, 4);                              // sAcc 50 mm/s
  return p;
}
}  // namespace

TEST(UbxFramer, GivenAKnownFrame_ThenTheFletcherChecksumMatchesTheSpecExample) {
  // UBX-CFG-PRT poll for port 1 (class 06 id 00 length 1 payload 01): checksum 08 22.
  const std::vector<std::uint8_t> body = {0x06, 0x00, 0x01, 0x00, 0x01};
  const auto [a, b] = ubx_checksum(body);
  EXPECT_EQ(a, 0x08);
  EXPECT_EQ(b, 0x22);
}

TEST(UbxNavPvt, GivenASyntheticPayload_ThenEveryFieldConvertsToSi) {
  const auto payload = nav_pvt_payload();
  const auto pvt = decode_nav_pvt(payload);
  ASSERT_TRUE(pvt);
  const auto s = solution_from_nav_pvt(*pvt);
  ASSERT_TRUE(s);
  EXPECT_EQ(s->time.week, 2320);
  EXPECT_NEAR(s->time.sow_s, 116400.2496, 1e-9);  // UTC 08:19:42.2496 + 18 s
  EXPECT_NEAR(s->fix.pos.lat_rad, 35.1346990 * kUbxDeg_rad, 1e-12);
  EXPECT_NEAR(s->fix.pos.lon_rad, 136.9775755 * kUbxDeg_rad, 1e-12);
  EXPECT_NEAR(s->fix.pos.h_m, 104.862, 1e-9);
  EXPECT_EQ(s->fix.quality, GnssQuality::kFixed);
  EXPECT_EQ(s->fix.num_sats, 31);
  EXPECT_NEAR(s->fix.pos_std_ned_m.x(), 0.014 / std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(s->fix.pos_std_ned_m.z(), 0.010, 1e-12);
  EXPECT_TRUE(s->fix.has_velocity);
  EXPECT_NEAR(s->fix.vel_n_mps.x(), -1.5, 1e-12);
  EXPECT_NEAR(s->fix.vel_n_mps.y(), 0.25, 1e-12);
  EXPECT_NEAR(s->fix.vel_n_mps.z(), 0.02, 1e-12);

  auto float_payload = payload;
  float_payload[21] = 0x03 | (1 << 6);
  EXPECT_EQ(solution_from_nav_pvt(*decode_nav_pvt(float_payload))->fix.quality, GnssQuality::kFloat);
  auto no_fix = payload;
  no_fix[21] = 0;
  EXPECT_FALSE(solution_from_nav_pvt(*decode_nav_pvt(no_fix)));
  EXPECT_FALSE(decode_nav_pvt(std::span(payload).first(91)));
}

TEST(UbxTimTp, GivenASyntheticPayload_ThenTheNextPulseLabelIsGpsTime) {
  std::vector<std::uint8_t> p(kUbxTimTpBytes, 0);
  put(p, 0, 116401000, 4);            // next pulse at 116401 s
  put(p, 4, 0x80000000u, 4);          // + 2^31 * 2^-32 ms = 0.5 ms
  put(p, 8, static_cast<std::uint32_t>(-2500), 4);  // qErr -2.5 ns
  put(p, 12, 2320, 2);
  p[14] = 0x02;                       // GNSS time base, UTC available
  p[15] = 0x00;                       // GPS
  const auto tp = decode_tim_tp(p);
  ASSERT_TRUE(tp);
  const auto label = label_from_tim_tp(*tp);
  ASSERT_TRUE(label);
  EXPECT_EQ(label->refers, PpsTimeLabel::Refers::kNextPulse);
  EXPECT_EQ(label->pulse_time.week, 2320);
  EXPECT_NEAR(label->pulse_time.sow_s, 116401.0005, 1e-10);
  EXPECT_NEAR(label->quantization_error_s, -2.5e-9, 1e-15);
  p[14] = 0x01;  // UTC time base: not a GPS label
  EXPECT_FALSE(label_from_tim_tp(*decode_tim_tp(p)));
}

TEST(UbxFramer, GivenFramesBehindGarbageFalseSyncsAndCorruption_WhenFedByteByByte_ThenGoodFramesAreAllRecovered) {
  const auto pvt = ubx_encode(kUbxClassNav, kUbxIdNavPvt, nav_pvt_payload());
  auto corrupted = pvt;
  corrupted[40] ^= 0x55;
  std::vector<std::uint8_t> stream = {0x00, 0xB5, 0x13, 0xB5};  // garbage and false starts
  stream.insert(stream.end(), pvt.begin(), pvt.end());
  // A false sync pair whose "length" swallows the next real frame: resync must find it inside.
  stream.insert(stream.end(), {0xB5, 0x62, 0x01, 0x07, 0x20, 0x00});
  stream.insert(stream.end(), pvt.begin(), pvt.end());
  stream.insert(stream.end(), corrupted.begin(), corrupted.end());
  stream.insert(stream.end(), pvt.begin(), pvt.begin() + 50);  // truncated
  stream.insert(stream.end(), pvt.begin(), pvt.end());

  int good = 0;
  UbxFramer framer([&](const UbxFrame& f) {
    if (f.msg_class == kUbxClassNav && f.msg_id == kUbxIdNavPvt && decode_nav_pvt(f.payload)) ++good;
  });
  for (std::uint8_t b : stream) framer.feed(std::span(&b, 1));
  EXPECT_EQ(good, 3);  // before and after the false sync, and after the truncated one
  EXPECT_EQ(framer.counters().bad_checksum, 3u);  // false sync, corrupted, truncated
}

TEST(UbxRealReceiver, GivenTheWalkUbxBytes_ThenEveryNavPvtDecodesAndMatchesTheRtklibPosOfTheWalk) {
  std::ifstream in(kWalk + "gnss_1730.ubx", std::ios::binary);
  ASSERT_TRUE(in) << "missing " << kWalk;
  const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());

  std::vector<GnssSolution> pvts;
  std::map<std::pair<int, int>, int> frame_types;
  int tim_tp = 0;
  std::vector<double> height_msl_m;
  UbxFramer framer([&](const UbxFrame& f) {
    ++frame_types[{f.msg_class, f.msg_id}];
    if (f.msg_class == kUbxClassNav && f.msg_id == kUbxIdNavPvt) {
      const auto pvt = decode_nav_pvt(f.payload);
      ASSERT_TRUE(pvt);
      const auto s = solution_from_nav_pvt(*pvt);
      ASSERT_TRUE(s);
      pvts.push_back(*s);
      height_msl_m.push_back(pvt->height_msl_mm * 1e-3);
    }
    if (f.msg_class == kUbxClassTim && f.msg_id == kUbxIdTimTp) ++tim_tp;
  });
  // The service gets serial chunks: feed 4 kB at a time.
  for (std::size_t i = 0; i < bytes.size(); i += 4096) {
    framer.feed(std::span(bytes).subspan(i, std::min<std::size_t>(4096, bytes.size() - i)));
  }
  EXPECT_EQ(pvts.size(), 536u);
  EXPECT_EQ(framer.counters().bad_checksum, 0u);
  EXPECT_EQ(tim_tp, 0);  // this log has NAV-PVT, RXM-RAWX and RXM-SFRBX only
  std::printf("[ walk UBX ] frames %llu (NAV-PVT %d, RXM-RAWX %d, RXM-SFRBX %d), TIM-TP %d, bytes outside frames "
              "%llu (the receiver's NMEA)\n",
              static_cast<unsigned long long>(framer.counters().frames), frame_types[{0x01, 0x07}],
              frame_types[{0x02, 0x15}], frame_types[{0x02, 0x13}], tim_tp,
              static_cast<unsigned long long>(framer.counters().garbage_bytes));

  // The RTKLIB .pos of the same walk, matched epoch by epoch (within 1 ms).
  const auto pos = read_rtklib_pos(kWalk + "gnss_1730_sf.pos");
  ASSERT_EQ(pos.size(), 536u);
  std::size_t matched = 0, same_quality = 0;
  double max_horizontal_m = 0, sum_h2 = 0, max_msl_dh_m = 0, sum_ellipsoid_dh = 0;
  for (std::size_t i = 0; i < pvts.size(); ++i) {
    const GnssSolution& u = pvts[i];
    const auto it = std::find_if(pos.begin(), pos.end(), [&](const GnssSolution& r) {
      return r.time.week == u.time.week && std::abs(r.time.sow_s - u.time.sow_s) < 1e-3;
    });
    if (it == pos.end()) continue;
    ++matched;
    const Vec3 d_ned = earth::ned_between(it->fix.pos, u.fix.pos);
    max_horizontal_m = std::max(max_horizontal_m, d_ned.head<2>().norm());
    sum_h2 += d_ned.head<2>().squaredNorm();
    max_msl_dh_m = std::max(max_msl_dh_m, std::abs(it->fix.pos.h_m - height_msl_m[i]));
    sum_ellipsoid_dh += it->fix.pos.h_m - u.fix.pos.h_m;
    same_quality += it->fix.quality == u.fix.quality;
  }
  const double n = static_cast<double>(matched);
  std::printf("[ walk UBX vs .pos ] matched %zu/536 epochs, same quality %zu, horizontal RMS %.4f m max %.4f m, "
              ".pos height - NAV-PVT hMSL max %.4f m, .pos height - NAV-PVT ellipsoidal height mean %.3f m\n",
              matched, same_quality, std::sqrt(sum_h2 / n), max_horizontal_m, max_msl_dh_m, sum_ellipsoid_dh / n);
  EXPECT_EQ(matched, 536u);
  EXPECT_EQ(same_quality, 536u);
  EXPECT_LT(max_horizontal_m, 0.02);  // NAV-PVT's 1e-7 deg resolution is 1.1 cm
  // The .pos heights are above the geoid (hMSL), not the ellipsoid: GGA's separation is -21.387 m.
  EXPECT_LT(max_msl_dh_m, 0.002);
  EXPECT_NEAR(sum_ellipsoid_dh / n, 21.387, 0.01);
}

TEST(UbxRealReceiver, GivenTheNmeaInterleavedInTheUbxBytes_ThenGgaAgreesWithNavPvtEpochByEpoch) {
  std::ifstream in(kWalk + "gnss_1730.ubx", std::ios::binary);
  ASSERT_TRUE(in);
  const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::vector<GnssSolution> nmea, ubx;
  NmeaEpochAssembler assembler([&](const GnssSolution& s) { nmea.push_back(s); });
  NmeaFramer nmea_framer([&](std::string_view s) { assembler.on_sentence(s); });
  UbxFramer ubx_framer([&](const UbxFrame& f) {
    if (f.msg_class == kUbxClassNav && f.msg_id == kUbxIdNavPvt) ubx.push_back(*solution_from_nav_pvt(*decode_nav_pvt(f.payload)));
  });
  // One port, two protocols: both framers see every byte.
  for (std::size_t i = 0; i < bytes.size(); i += 1000) {
    const auto chunk = std::span(bytes).subspan(i, std::min<std::size_t>(1000, bytes.size() - i));
    nmea_framer.feed(chunk);
    ubx_framer.feed(chunk);
  }
  assembler.flush();
  const auto& c = nmea_framer.counters();
  std::printf("[ walk NMEA ] sentences %llu, bad checksum %llu, truncated %llu, solutions %zu\n",
              static_cast<unsigned long long>(c.sentences), static_cast<unsigned long long>(c.bad_checksum),
              static_cast<unsigned long long>(c.truncated), nmea.size());
  EXPECT_EQ(c.bad_checksum, 0u);
  ASSERT_EQ(nmea.size(), ubx.size());
  double max_h = 0, max_dh = 0, max_dt = 0;
  for (std::size_t i = 0; i < nmea.size(); ++i) {
    max_h = std::max(max_h, earth::ned_between(ubx[i].fix.pos, nmea[i].fix.pos).head<2>().norm());
    max_dh = std::max(max_dh, std::abs(ubx[i].fix.pos.h_m - nmea[i].fix.pos.h_m));
    max_dt = std::max(max_dt, std::abs(ubx[i].time.sow_s - nmea[i].time.sow_s));
    EXPECT_EQ(ubx[i].fix.quality, nmea[i].fix.quality) << i;
  }
  std::printf("[ walk NMEA vs NAV-PVT ] max horizontal %.4f m, max height %.4f m, max time %.6f s\n", max_h, max_dh,
              max_dt);
  EXPECT_LT(max_h, 0.012);
  EXPECT_LT(max_dh, 0.002);
  EXPECT_LT(max_dt, 1e-3);  // GGA prints the nominal epoch; NAV-PVT's nanoseconds give the exact one
}
