// RTKLIB solution text: every layout rnx2rtkp/rtkrcv print (hand-written lines for one known
// point), the covariance conventions, and the chunked TCP stream with malformed lines.
#include <gtest/gtest.h>

#include <numbers>
#include <string>
#include <vector>

#include "common/geo/earth_model.hpp"
#include "common/io/input_error.hpp"
#include "common/formats/rtklib_solution.hpp"
#include "common/formats/rtklib_solution_stream.hpp"

using namespace ldv;
using namespace ldv::gnss;

namespace {
constexpr double kRtklibDeg_rad = std::numbers::pi / 180.0;
// The septentrio rover's known position (data README) and the base.
const Geodetic kRover{35.13469901 * kRtklibDeg_rad, 136.97757549 * kRtklibDeg_rad, 104.8626};
const Geodetic kBase{35.134707705 * kRtklibDeg_rad, 136.977577939 * kRtklibDeg_rad, 104.853};

std::vector<GnssSolution> parse_all(const std::string& text, RtklibStreamCounters* counters = nullptr,
                                    RtklibParserOptions options = {}) {
  std::vector<GnssSolution> out;
  RtklibSolutionStream stream([&](const GnssSolution& s) { out.push_back(s); }, options);
  stream.feed(text);
  stream.flush();
  if (counters) *counters = stream.counters();
  return out;
}

void expect_rover(const GnssSolution& s, double tol_m = 1e-4) {
  const Vec3 d = earth::ned_between(kRover, s.fix.pos);
  EXPECT_LT(d.norm(), tol_m) << d.transpose();
}
}  // namespace

TEST(RtklibSolution, GivenAnLlhLineWithVelocity_ThenEveryColumnLandsInTheSolution) {
  const auto s = parse_all(
      "%  GPST                  latitude(deg) longitude(deg)  height(m)   Q  ns   sdn(m)   sde(m)   sdu(m)  sdne(m)  "
      "sdeu(m)  sdun(m) age(s)  ratio    vn(m/s)    ve(m/s)    vu(m/s)      sdvn     sdve     sdvu    sdvne    sdveu    sdvun\n"
      "2024/06/24 08:20:00.000   35.134699010  136.977575490   104.8626   1  42   0.0024   0.0030   0.0069   0.0008  "
      "-0.0013  -0.0024   1.50   12.0    0.00141   -0.00126   -0.01073   0.05834  0.05764  0.15666  0.01063 -0.03203 -0.04989\n");
  ASSERT_EQ(s.size(), 1u);
  const GnssSolution& x = s[0];
  EXPECT_EQ(x.time.week, 2320);
  EXPECT_NEAR(x.time.sow_s, 116400.0, 1e-9);
  expect_rover(x);
  EXPECT_EQ(x.fix.quality, GnssQuality::kFixed);
  EXPECT_EQ(x.fix.num_sats, 42);
  EXPECT_DOUBLE_EQ(x.fix.age_s, 1.5);
  EXPECT_DOUBLE_EQ(x.fix.ratio, 12.0);
  EXPECT_NEAR(x.fix.pos_std_ned_m.x(), 0.0024, 1e-12);
  EXPECT_NEAR(x.fix.pos_std_ned_m.y(), 0.0030, 1e-12);
  EXPECT_NEAR(x.fix.pos_std_ned_m.z(), 0.0069, 1e-12);
  // Signed square roots: sdne = 0.0008 -> +6.4e-7 m^2; sdeu = -0.0013 -> cov(e,u) = -1.69e-6, so cov(e,d) = +1.69e-6.
  EXPECT_NEAR(x.pos_cov_ned_m2(0, 1), 6.4e-7, 1e-15);
  EXPECT_NEAR(x.pos_cov_ned_m2(1, 2), 1.69e-6, 1e-15);
  EXPECT_NEAR(x.pos_cov_ned_m2(2, 0), 5.76e-6, 1e-15);  // sdun = -0.0024 -> cov(u,n) < 0 -> cov(d,n) > 0
  ASSERT_TRUE(x.fix.has_velocity);
  EXPECT_NEAR(x.fix.vel_n_mps.x(), 0.00141, 1e-12);
  EXPECT_NEAR(x.fix.vel_n_mps.y(), -0.00126, 1e-12);
  EXPECT_NEAR(x.fix.vel_n_mps.z(), 0.01073, 1e-12);  // down = -up
  EXPECT_NEAR(x.fix.vel_std_n_mps.z(), 0.15666, 1e-12);
}

TEST(RtklibSolution, GivenWeekTowTimeAndNoHeader_ThenTheLayoutIsInferred) {
  const auto s = parse_all("2320 116401.500   35.134699010  136.977575490   104.8626   2  12   0.1 0.1 0.2 0 0 0 0.0 0.0\n");
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(s[0].time.week, 2320);
  EXPECT_NEAR(s[0].time.sow_s, 116401.5, 1e-9);
  EXPECT_EQ(s[0].fix.quality, GnssQuality::kFloat);
  EXPECT_FALSE(s[0].fix.has_velocity);
  expect_rover(s[0]);
}

TEST(RtklibSolution, GivenEcefLines_ThenPositionAndCovarianceAreRotatedToNed) {
  const Vec3 r = earth::ecef_from_geodetic(kRover);
  // An ECEF covariance that is 0.01 m^2 along local north only: C_n_e * diag(0.01,0,0) * C_n_e^T.
  const Mat3 C = earth::C_n_e(kRover);
  const Mat3 P = C * Vec3(1e-4, 0, 0).asDiagonal() * C.transpose();
  auto ss = [](double c) { return c < 0 ? -std::sqrt(-c) : std::sqrt(c); };
  char line[512];
  std::snprintf(line, sizeof line, "2024/06/24 08:20:00.000 %.4f %.4f %.4f 1 10 %.6f %.6f %.6f %.6f %.6f %.6f 0 5\n",
                r.x(), r.y(), r.z(), ss(P(0, 0)), ss(P(1, 1)), ss(P(2, 2)), ss(P(0, 1)), ss(P(1, 2)), ss(P(2, 0)));
  for (const std::string header : {"", "%  GPST                      x-ecef(m)      y-ecef(m)      z-ecef(m)   Q  ns\n"}) {
    const auto s = parse_all(header + line);
    ASSERT_EQ(s.size(), 1u);
    expect_rover(s[0], 2e-4);
    EXPECT_NEAR(s[0].fix.pos_std_ned_m.x(), 0.01, 2e-5);
    EXPECT_NEAR(s[0].fix.pos_std_ned_m.y(), 0.0, 2e-3);
    EXPECT_NEAR(s[0].fix.pos_std_ned_m.z(), 0.0, 2e-3);
  }
}

TEST(RtklibSolution, GivenEnuBaselineWithRefPosHeader_ThenTheAbsolutePositionIsBasePlusBaseline) {
  const Vec3 baseline_ned = earth::ned_between(kBase, kRover);
  char text[1024];
  std::snprintf(text, sizeof text,
                "%% ref pos   : 35.134707705 136.977577939  104.8530\n"
                "%%  GPST                   e-baseline(m)  n-baseline(m)  u-baseline(m)   Q  ns\n"
                "2024/06/24 08:20:00.000 %.4f %.4f %.4f 1 42 0.003 0.002 0.007 0 0 0 0.0 9.9\n",
                baseline_ned.y(), baseline_ned.x(), -baseline_ned.z());
  const auto s = parse_all(text);
  ASSERT_EQ(s.size(), 1u);
  expect_rover(s[0], 2e-4);
  EXPECT_NEAR(s[0].fix.pos_std_ned_m.x(), 0.002, 1e-12);  // sdn is the second column in e/n/u
  EXPECT_NEAR(s[0].fix.pos_std_ned_m.y(), 0.003, 1e-12);
  // Without a base the baseline cannot be placed: malformed, not a wrong position.
  RtklibStreamCounters c;
  parse_all("%  GPST  e-baseline(m)  n-baseline(m)  u-baseline(m)\n2024/06/24 08:20:00.000 1 2 3 1 42 0 0 0 0 0 0 0 0\n", &c);
  EXPECT_EQ(c.malformed_lines, 1u);
}

TEST(RtklibSolution, GivenDmsLatLonAndUtcTime_ThenBothAreConverted) {
  const auto s = parse_all(
      "%  UTC                   latitude(d'\")   longitude(d'\")  height(m)   Q  ns\n"
      "2024/06/24 08:19:42.000   35 08 04.916436  136 58 39.271764   104.8626   5   8   1 1 2 0 0 0 0.0 0.0\n");
  ASSERT_EQ(s.size(), 1u);
  EXPECT_NEAR(s[0].time.sow_s, 116400.0, 1e-9);  // UTC + 18 s
  EXPECT_EQ(s[0].fix.quality, GnssQuality::kSingle);
  expect_rover(s[0], 1e-3);
}

TEST(RtklibSolutionStream, GivenChunkedTcpBytesWithBadLines_ThenGoodLinesSurviveAndBadOnesAreCounted) {
  const std::string good = "2024/06/24 08:20:00.000   35.134699010  136.977575490   104.8626   1  42   0.0024   0.0024   0.0069   0.0008  -0.0013  -0.0024   0.00   12.0\r\n";
  std::string text = "% program   : RTKLIB ver.2.4.3\n" + good;
  text += "2024/06/24 08:20:01.000   35.1346990x0  136.977575490   104.8626   1  42 0 0 0 0 0 0 0 0\n";  // bad number
  text += "2024/06/24 08:20:02.000   35.134699010  136.977575490\n";                                  // truncated
  text += "2024/06/24 08:20:03.000   35.134699010  136.977575490   104.8626   0  42 0 0 0 0 0 0 0 0\n";  // Q=0
  text += std::string(5000, 'x') + "\n";                                                           // overlong
  text += good;
  std::vector<GnssSolution> out;
  RtklibSolutionStream stream([&](const GnssSolution& s) { out.push_back(s); });
  for (std::size_t i = 0; i < text.size(); i += 13) stream.feed(std::string_view(text).substr(i, 13));
  EXPECT_EQ(out.size(), 2u);
  EXPECT_EQ(stream.counters().header_lines, 1u);
  EXPECT_EQ(stream.counters().malformed_lines, 3u);
  EXPECT_EQ(stream.counters().overlong_lines, 1u);
}

TEST(RtklibSolution, GivenAMalformedLine_ThenReadingSkipsAndCountsItByReason) {
  const std::string path = ::testing::TempDir() + "bad.pos";
  FILE* f = std::fopen(path.c_str(), "w");
  std::fputs("% header\n2024/06/24 garbage\n", f);
  for (int k = 0; k < 10; ++k)  // one bad line in eleven: under the 10 % that makes it a wrong file
    std::fprintf(f, "2024/06/24 08:20:%02d.000 35.1 136.9 104.8 1 42 0.01 0.01 0.02 0 0 0 0 0\n", k);
  std::fclose(f);
  RtklibReadReport report;
  const auto sols = read_rtklib_pos(path, {}, &report);
  EXPECT_EQ(sols.size(), 10u);
  EXPECT_EQ(report.first_line_by_reason.at("expected 'yyyy/mm/dd hh:mm:ss' or 'week tow'"), 2);
  EXPECT_EQ(report.malformed(), 1);
  EXPECT_EQ(report.malformed_by_reason.count("expected 'yyyy/mm/dd hh:mm:ss' or 'week tow'"), 1u);
}

TEST(RtklibSolution, GivenOnlyMalformedLines_ThenReadingThrowsWithFileAndLine) {
  const std::string path = ::testing::TempDir() + "all_bad.pos";
  FILE* f = std::fopen(path.c_str(), "w");
  std::fputs("% header\n2024/06/24 garbage\n2024/06/24 08:20:00.000 35.1 136.9 104.8 1 42 0 0 0 0 0 0 0 0\n", f);
  std::fclose(f);
  try {
    read_rtklib_pos(path);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 2);
    EXPECT_NE(std::string(e.what()).find("1 malformed (position sigma not positive, first at line 3)"), std::string::npos) << e.what();
  }
}

TEST(RtklibSolution, GivenNonPositiveOrNonFiniteSigmas_ThenTheLineIsMalformed) {
  RtklibSolutionParser parser;
  GnssSolution s;
  std::string why;
  const std::string head = "2024/06/24 08:20:00.000 35.1 136.9 104.8 1 42 ";
  EXPECT_EQ(parser.parse_line(head + "0.01 0.01 0.02 0 0 0 0 0", s, &why), RtklibSolutionParser::LineKind::kSolution);
  for (const char* sigmas : {"0 0.01 0.02", "0.01 -0.01 0.02", "0.01 0.01 0", "0.01 nan 0.02", "0.01 0.01 inf"}) {
    EXPECT_EQ(parser.parse_line(head + sigmas + " 0 0 0 0 0", s, &why), RtklibSolutionParser::LineKind::kMalformed)
        << sigmas;
  }
}

// Found by the fuzzer (tests/fuzz/corpus/fuzz_rtklib_files/finding_q_cast_overflow): a Q or a satellite count of
// 1e300 was cast to int (undefined behaviour). Now a malformed line by reason.
TEST(RtklibSolution, GivenAQOrSatelliteCountBeyondAnInt_ThenTheLineIsMalformed) {
  RtklibSolutionParser parser;
  GnssSolution s;
  std::string why;
  EXPECT_EQ(parser.parse_line("2300 1000.000 35.1 136.9 104.8 1e300 10 0.01 0.01 0.02 0 0 0 0.0 9.9", s, &why),
            RtklibSolutionParser::LineKind::kMalformed);
  EXPECT_EQ(why, "expected Q in 1..6");
  EXPECT_EQ(parser.parse_line("2300 1000.000 35.1 136.9 104.8 1 1e300 0.01 0.01 0.02 0 0 0 0.0 9.9", s, &why),
            RtklibSolutionParser::LineKind::kMalformed);
  EXPECT_EQ(why, "expected a satellite count in 0..1000");
  EXPECT_EQ(parser.parse_line("2300 1000.000 35.1 136.9 104.8 1 10 0.01 0.01 0.02 0 0 0 0.0 9.9", s, &why),
            RtklibSolutionParser::LineKind::kSolution);
}
