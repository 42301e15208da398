// gnss_link's boundary: decoded but impossible solutions (week 5,114,391, height 1e308, negative
// variances) are counted as malformed and never published.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "common/formats/gnss_solution_checks.hpp"
#include "services/gnss_link/gnss_stream_decoder.hpp"

using namespace ldv::gnss;

namespace {
std::vector<GnssSolution> decode_rtklib(const std::string& text, GnssDecoderCounters* c) {
  std::vector<GnssSolution> out;
  GnssDecoderOptions o;
  o.protocol = LinkProtocol::kRtklib;
  GnssStreamDecoder d(
      o, [&](const GnssSolution& s) { out.push_back(s); }, nullptr);
  d.feed({reinterpret_cast<const std::uint8_t*>(text.data()), text.size()});
  d.flush_end_of_input();
  *c = d.counters();
  return out;
}
GnssSolution good() {
  GnssSolution s;
  s.time = {2300, 1000.0};
  s.fix.t_s = 1000.0;
  s.fix.pos = {0.6, 2.4, 100.0};
  s.pos_cov_ned_m2 = ldv::Mat3::Identity() * 1e-4;
  sync_std_from_cov(s);
  return s;
}
}  // namespace

TEST(GnssPlausibility, GivenImpossibleFields_ThenEachIsNamed) {
  EXPECT_FALSE(implausibility(good()));
  GnssSolution s = good();
  s.time.week = 5114391;
  EXPECT_NE(implausibility(s)->find("GPS week 5114391"), std::string::npos);
  s = good();
  s.time.sow_s = 3085367.0;
  EXPECT_NE(implausibility(s)->find("time of week 3.08537e+06 s"), std::string::npos);
  s = good();
  s.fix.pos.h_m = 1e308;
  EXPECT_NE(implausibility(s)->find("height 1e+308 m"), std::string::npos);
  s = good();
  s.pos_cov_ned_m2(1, 1) = -1e-4;
  EXPECT_NE(implausibility(s)->find("position variances"), std::string::npos);
}

TEST(GnssPlausibility, GivenRtklibLinesWithAnImpossibleWeekOrHeight_ThenTheyAreDroppedAndCounted) {
  const std::string ok = "2300 1000.000 35.1 136.9 104.8 1 10 0.01 0.01 0.02 0 0 0 0.0 9.9\n";
  const std::string text = ok + "5114391 1001.000 35.1 136.9 104.8 1 10 0.01 0.01 0.02 0 0 0 0.0 9.9\n" +
                           "2300 1002.000 35.1 136.9 1e308 1 10 0.01 0.01 0.02 0 0 0 0.0 9.9\n" +
                           "2300 1003.000 35.1 136.9 104.8 1 10 0.01 0.01 0.02 0 0 0 0.0 9.9\n";
  GnssDecoderCounters c;
  const auto sols = decode_rtklib(text, &c);
  ASSERT_EQ(sols.size(), 2u);
  EXPECT_DOUBLE_EQ(sols[1].time.sow_s, 1003.0);
  EXPECT_EQ(c.implausible, 2u);
  EXPECT_EQ(c.rejected_total(), 2u);  // the heartbeat's malformed count includes them
}
