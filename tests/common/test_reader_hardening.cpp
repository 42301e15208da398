// Issue 13 (file readers and writers): each defect reproduced and its fix checked, against values computed
// here independently of the readers.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>

#include "common/formats/imu_sample_checks.hpp"
#include "common/formats/kfgins_config.hpp"
#include "common/formats/kfgins_files.hpp"
#include "common/formats/rtklib_time_tag.hpp"
#include "common/formats/tagged_imu_csv.hpp"
#include "common/io/atomic_file.hpp"
#include "common/io/input_error.hpp"
#include "common/io/output_file.hpp"
#include "common/io/text_table.hpp"
#include "common/time/gps_time.hpp"

using namespace ldv;
namespace fs = std::filesystem;

namespace {
std::string temp_path(const std::string& name) { return (fs::temp_directory_path() / ("ldv_hard_" + name)).string(); }
std::string write_temp(const std::string& name, const std::string& text) {
  const std::string p = temp_path(name);
  std::ofstream(p, std::ios::binary) << text;
  return p;
}
std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}
std::string imu_line(double t_s, int columns = 7) {
  std::string s = std::to_string(t_s);
  for (int c = 1; c < columns; ++c) s += " 0.001";
  return s + "\n";
}
std::string imu_file(int n, double t0 = 100.0, double dt = 0.01) {
  std::string s;
  for (int i = 0; i < n; ++i) s += imu_line(t0 + dt * i);
  return s;
}
}  // namespace

// Defect 1: format_fixed wrote stale buffer bytes for |value| beyond ~1e57.
TEST(FormatFixed, HugeAndNonFiniteValuesAreWrittenAsDefinedText) {
  for (double v : {1e57, -1e58, 1e300, -1.7976931348623157e308, 123456789012345678901.0, 1e21}) {
    char buf[kFormatFixedMaxChars + 16];
    std::memset(buf, 'X', sizeof buf);
    const int n = format_fixed(buf, v, 6);
    ASSERT_GT(n, 0);
    ASSERT_LE(n, kFormatFixedMaxChars);
    const std::string text(buf, static_cast<size_t>(n));
    EXPECT_EQ(text.find('X'), std::string::npos) << text;
    EXPECT_EQ(std::strtod(text.c_str(), nullptr), v) << text;  // parses back exactly
  }
  char buf[kFormatFixedMaxChars];
  EXPECT_EQ(std::string(buf, format_fixed(buf, std::nan(""), 6)), "nan");
  EXPECT_EQ(std::string(buf, format_fixed(buf, -INFINITY, 6)), "-inf");
  EXPECT_EQ(std::string(buf, format_fixed(buf, 12.5, 3)), "12.500");  // the fast path unchanged
}

TEST(NavWriter, AnAbsurdHeightIsWrittenAsANumberAndNanIsRefusedKeepingEarlierRows) {
  const std::string p = temp_path("absurd.nav");
  NavRecord r;
  r.week = 2380;
  r.sow_s = 1000.0;
  r.pos = {0.5, 1.0, 10.0};
  {
    NavWriter w(p);
    w.write(r);
    r.sow_s += 1;
    r.pos.h_m = -4.6e15 * 1e50;  // a diverged filter
    w.write(r);
    w.close();
  }
  const auto back = read_nav(p);
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[1].pos.h_m, -4.6e65);
  EXPECT_EQ(back[1].week, 2380);

  NavWriter w(p);
  r.pos.h_m = 1.0;
  w.write(r);
  r.sow_s = 1234.5;
  r.vel_n_mps.y() = std::nan("");
  const std::string e = error_of([&] { w.write(r); });
  EXPECT_NE(e.find(p + ":2: cannot write a non-finite vE"), std::string::npos) << e;
  EXPECT_NE(e.find("week 2380, 1234.500000 s"), std::string::npos) << e;
  w.close();
  EXPECT_EQ(read_nav(p).size(), 1u);  // the row before it is kept
}

// Defect 2: no line length limit, devices read forever.
TEST(BoundedLines, DevicesAndEndlessLinesEndInAClearError) {
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_NE(error_of([] { read_kfgins_imu("/dev/zero"); }).find("/dev/zero: is a character device"), std::string::npos);
  EXPECT_NE(error_of([] { read_kfgins_gnss("/dev/zero"); }).find("character device"), std::string::npos);
  EXPECT_NE(error_of([] { load_kfgins_config("/dev/zero"); }).find("character device"), std::string::npos);
  EXPECT_NE(error_of([] { read_nav(fs::temp_directory_path().string()); }).find("is a directory"), std::string::npos);
  const std::string tag = write_temp("any.tag", std::string("TIMETAG RTKLIB EX") + std::string(60 - 17 + 16 + 8, '\0'));
  EXPECT_NE(error_of([&] { read_tagged_imu_csv("/dev/zero", tag); }).find("/dev/zero"), std::string::npos);
  // A regular file with one endless line: refused at the limit, naming file and line.
  const std::string p = write_temp("long_line.txt", imu_file(2) + std::string(200000, '1') + "\n");
  EXPECT_NE(error_of([&] { read_kfgins_imu(p); }).find("long_line.txt:3: line longer than 65536 bytes"),
            std::string::npos);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 5.0);
}

// Defect 3: the IMU reader took 7 to 64 columns whatever imudatalen said.
TEST(KfGinsImuColumns, ALineWithAnotherColumnCountIsDroppedCountedAndNamed) {
  std::string text = imu_file(100);
  // One corrupted byte: '.' -> ' ' turns "100.500000" into two columns, the row shifts by one.
  const size_t at = text.find("100.500000");
  text[at + 3] = ' ';
  const std::string p = write_temp("imu_shift.txt", text);
  ImuReadReport rep;
  const auto imu = read_kfgins_imu(p, &rep);
  EXPECT_EQ(imu.size(), 99u);
  EXPECT_EQ(rep.dropped[DropReason::kWrongColumns], 1);
  EXPECT_NE(rep.dropped.describe().find("imu_shift.txt:51: expected 7 columns"), std::string::npos)
      << rep.dropped.describe();
  // The declared count is enforced: an 8-column file with imudatalen 7 is refused, with 8 it is read.
  std::string eight;
  for (int i = 0; i < 50; ++i) eight += imu_line(100 + 0.01 * i, 8);
  const std::string p8 = write_temp("imu8.txt", eight);
  EXPECT_NE(error_of([&] { read_kfgins_imu(p8); }).find("50 of 50 data lines dropped"), std::string::npos);
  ImuReadOptions o;
  o.columns = 8;
  EXPECT_EQ(read_kfgins_imu(p8, nullptr, o).size(), 50u);
}

TEST(KfGinsGnssColumns, TheFirstDataLineDecidesSevenOrThirteen) {
  std::string text;
  for (int i = 0; i < 30; ++i)
    text += std::to_string(100 + i) + " 30.1 114.2 20.0 0.01 0.02 0.03" + (i == 7 ? " 1 2 3 0.1 0.2 0.3\n" : "\n");
  const std::string p = write_temp("gnss_mixed.txt", text);
  GnssReadReport rep;
  const auto g = read_kfgins_gnss(p, &rep);
  EXPECT_EQ(g.size(), 29u);
  EXPECT_EQ(rep.columns, 7);
  EXPECT_EQ(rep.dropped[DropReason::kWrongColumns], 1);
  EXPECT_NE(rep.dropped.first[static_cast<int>(DropReason::kWrongColumns)].find("gnss_mixed.txt:8:"),
            std::string::npos);
}

// Issue 46, readers that disagree: gnss.txt took a height of -1e7 m and a std of 1e200 m (whose square is inf, which
// then reached the innovations file and the diagnosis) that the .pos reader and the bus refuse. One check for all
// (gnss::implausibility of the fix): each such row is dropped, counted and named by its line.
TEST(KfGinsGnssPlausibility, GivenRowsTheRtklibReaderRefuses_ThenGnssTxtDropsThemByLine) {
  std::string text;
  for (int i = 0; i < 60; ++i) {
    std::string row = std::to_string(100 + i) + " 30.1 114.2 20.0 0.01 0.02 0.03\n";
    if (i == 10) row = "110 30.1 114.2 -1e7 0.01 0.02 0.03\n";   // a height below any ellipsoidal one
    if (i == 20) row = "120 30.1 114.2 20.0 1e200 0.02 0.03\n";  // its variance is inf
    if (i == 30) row = "130 30.1 114.2 1e300 0.01 0.02 0.03\n";  // above any flight
    text += row;
  }
  const std::string p = write_temp("gnss_implausible.txt", text);
  GnssReadReport rep;
  const auto g = read_kfgins_gnss(p, &rep);
  EXPECT_EQ(g.size(), 57u);
  EXPECT_EQ(rep.dropped[DropReason::kOutOfRange], 3);
  const std::string& first = rep.dropped.first[static_cast<int>(DropReason::kOutOfRange)];
  EXPECT_NE(first.find("gnss_implausible.txt:11:"), std::string::npos) << first;
  EXPECT_NE(first.find("height"), std::string::npos) << first;
  for (const GnssFix& f : g) {
    EXPECT_TRUE(f.pos_std_ned_m.cwiseAbs2().allFinite());
    EXPECT_GT(f.pos.h_m, -1000.0);
    EXPECT_LT(f.pos.h_m, 1e5);
  }
}

// Issue 46 (4): the KF-GINS IMU reader had its own per-line caps (100 rad, 1e4 m/s per line), so 2 rad in 5 ms
// (400 rad/s) or 50 m/s in 5 ms (10000 m/s^2) passed while the bus refused them. One set of checks: the rates of
// imu_sample_checks over the line's interval; a normal increment after a gap is kept (a gap, not a bad sample).
TEST(KfGinsImuPlausibility, GivenIncrementsTheBusRefuses_ThenImuTxtDropsThemByLineAndKeepsTheGap) {
  std::string text;
  for (int i = 0; i < 200; ++i) {
    const double t = 100.0 + 0.005 * i + (i >= 150 ? 2.0 : 0.0);  // a 2 s gap before line 151
    char row[160];
    double dtheta = 1e-4, dvel = -0.049;
    if (i == 40) dtheta = 2.0;  // 400 rad/s: beyond any gyro, under the old 100 rad cap
    if (i == 80) dvel = 50.0;   // 10000 m/s^2: beyond any accelerometer, under the old 1e4 m/s cap
    std::snprintf(row, sizeof row, "%.3f %.6e 0 0 0 0 %.6e\n", t, dtheta, dvel);
    text += row;
  }
  const std::string p = write_temp("imu_implausible.txt", text);
  ImuReadReport rep;
  const auto imu = read_kfgins_imu(p, &rep);
  EXPECT_EQ(imu.size(), 198u);
  EXPECT_EQ(rep.dropped[DropReason::kOutOfRange], 2);
  const std::string& first = rep.dropped.first[static_cast<int>(DropReason::kOutOfRange)];
  EXPECT_NE(first.find("imu_implausible.txt:41:"), std::string::npos) << first;
  EXPECT_NE(first.find("angular rate"), std::string::npos) << first;
  EXPECT_EQ(rep.long_gaps.size(), 1u) << "the gap stays a gap";
  for (const ImuIncrement& s : imu) EXPECT_FALSE(imu_increment_implausibility(s.dtheta_b_rad, s.dvel_b_mps, 0.005));
}

// Defect 4: a 1e6 s hole was integrated as one increment and reported as "gaps 0".
TEST(KfGinsImuTime, HolesBackwardsRepeatsAndJumpsAreCountedByReason) {
  std::string text = imu_file(50);                            // 100.00 .. 100.49
  text += imu_file(50, 100.0 + 1e6);                          // a 1e6 s hole
  text.insert(text.find(imu_line(100.2)), imu_line(100.1));   // backwards (line 21)
  text.insert(text.find(imu_line(100.3)), imu_line(100.29));  // repeated (line 32: 100.29 twice)
  text.insert(text.find(imu_line(100.4)), imu_line(900.0));   // one corrupted time stamp, ahead of both neighbours
  const std::string p = write_temp("imu_time.txt", text);
  ImuReadReport rep;
  const auto imu = read_kfgins_imu(p, &rep);
  EXPECT_EQ(imu.size(), 100u);
  EXPECT_EQ(rep.dropped[DropReason::kTimeBackwards], 1);
  EXPECT_EQ(rep.dropped[DropReason::kRepeated], 1);
  EXPECT_EQ(rep.dropped[DropReason::kTimeJump], 1);
  ASSERT_EQ(rep.long_gaps.size(), 1u);
  EXPECT_NEAR(rep.long_gaps[0].length_s(), 1e6 - 0.49, 1e-3);
  EXPECT_NEAR(rep.long_gaps[0].t_before_s, 100.49, 1e-9);
  EXPECT_EQ(rep.long_gaps[0].line, 54);  // 50 + the three inserted lines + 1
  EXPECT_GE(rep.gaps, 1);
  for (size_t i = 1; i < imu.size(); ++i) ASSERT_GT(imu[i].t_s, imu[i - 1].t_s);
}

// Defect 5: tagged CSV counters. Builds a CSV and a tag file whose positions count the bytes as written here.
namespace {
struct TaggedFiles {
  std::string csv, tag;
};
void put_u32(std::string& s, uint32_t v) { s.append(reinterpret_cast<const char*>(&v), 4); }
// Samples every 10 counter ticks (ms) received at 100 Hz host time; positions counted with `tag_crlf` line ends,
// the CSV stored with `file_crlf` ones.
TaggedFiles tagged(const std::string& name, const std::vector<std::string>& counters, bool file_crlf, bool tag_crlf) {
  std::string csv, tag = "TIMETAG RTKLIB EX";
  tag.resize(60, '\0');
  put_u32(tag, 0);
  put_u32(tag, static_cast<uint32_t>(kGpsEpochInUnixSeconds + 1400000000.0));
  const double fraction = 0.0;
  tag.append(reinterpret_cast<const char*>(&fraction), 8);
  uint64_t counted = 0;
  for (size_t i = 0; i < counters.size(); ++i) {
    const std::string body = "0.0,0.0,1.0,0.0,0.0,0.0," + counters[i];
    csv += body + (file_crlf ? "\r\n" : "\n");
    counted += body.size() + (tag_crlf ? 2 : 1);
    put_u32(tag, static_cast<uint32_t>(10 * i + 3));   // tick of reception [ms]: 3 ms latency
    put_u32(tag, static_cast<uint32_t>(counted));      // as RTKLIB writes it: the position after the chunk
  }
  return {write_temp(name + ".csv", csv), write_temp(name + ".csv.tag", tag)};
}
std::vector<std::string> counters_from(uint64_t first, int n, uint64_t modulo = 0) {
  std::vector<std::string> c;
  for (int i = 0; i < n; ++i) {
    const uint64_t v = first + 10 * static_cast<uint64_t>(i);
    c.push_back(std::to_string(modulo ? v % modulo : v));
  }
  return c;
}
}  // namespace

// Two chunks as RTKLIB's writefile tags them (the position after each write): bytes 0-9 arrived at 100 ms, bytes
// 10-24 at 200 ms.
TEST(RtklibTimeTagFile, AByteArrivedWithTheChunkThatEndsBeyondIt) {
  std::string tag = "TIMETAG RTKLIB EX";
  tag.resize(60, '\0');
  put_u32(tag, 0);
  put_u32(tag, static_cast<uint32_t>(kGpsEpochInUnixSeconds + 1000.0));
  const double fraction = 0.5;
  tag.append(reinterpret_cast<const char*>(&fraction), 8);
  for (const auto& [tick_ms, end_pos] : {std::pair<uint32_t, uint32_t>{100, 10}, {200, 25}}) {
    put_u32(tag, tick_ms);
    put_u32(tag, end_pos);
  }
  const RtklibTimeTag t = read_rtklib_time_tag(write_temp("two_chunks.tag", tag));
  EXPECT_DOUBLE_EQ(t.start_gps_s, 1000.5);
  for (const auto& [byte, at_s] : {std::pair<uint64_t, double>{0, 0.1}, {9, 0.1}, {10, 0.2}, {24, 0.2}, {25, 0.2}})
    EXPECT_NEAR(t.reception_gps_s(byte) - t.start_gps_s, at_s, 1e-12) << "byte " << byte;
}

TEST(TaggedCsvCounters, HugeCountersEndAndAbsurdOnesAreRefusedWithTheirLine) {
  auto c = counters_from(18446744073709000000ull, 200);  // close to 2^64: the fit once looped forever
  c[100] = "45000000000000000000";                       // beyond 2^64
  const TaggedFiles f = tagged("huge", c, false, false);
  TaggedImuCsvReport rep;
  const auto t0 = std::chrono::steady_clock::now();
  const auto imu = read_tagged_imu_csv(f.csv, f.tag, {}, &rep);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 2.0);
  EXPECT_EQ(rep.samples, 199);
  EXPECT_EQ(rep.dropped[DropReason::kOutOfRange], 1);
  EXPECT_NE(rep.dropped.describe().find("huge.csv:101: column 7"), std::string::npos) << rep.dropped.describe();
  for (size_t i = 1; i < imu.size(); ++i) {
    const double expected = (i == 99 ? 0.02 : 0.01);  // the dropped sample leaves a 20 ms increment
    ASSERT_NEAR(imu[i].dt_s, expected, 1e-9) << i;
  }
}

TEST(TaggedCsvCounters, AThirtyTwoBitWrapIsUnwrapped) {
  const TaggedFiles f = tagged("wrap", counters_from(4294967296ull - 1000, 300, 4294967296ull), false, false);
  TaggedImuCsvReport rep;
  const auto imu = read_tagged_imu_csv(f.csv, f.tag, {}, &rep);
  EXPECT_EQ(rep.samples, 300);
  EXPECT_EQ(rep.counter_wraps, 1);
  EXPECT_EQ(rep.counter_bits, 32);
  EXPECT_EQ(rep.dropped.total(), 0);
  for (const auto& s : imu) ASSERT_NEAR(s.dt_s, 0.01, 1e-9);
  // Declared narrower than the values: refused as out of range.
  TaggedImuCsvOptions o;
  o.counter_bits = 16;
  EXPECT_NE(error_of([&] { read_tagged_imu_csv(f.csv, f.tag, o); }).find("wider than 16 bits"), std::string::npos);
}

// Issue 12 item 6: tag positions counted with CRLF, the CSV stored with LF (git). Counter and host clock run at the
// same rate here (10 ms per sample, 10 ms per tag tick), so the fitted host rate must be that of the counter.
TEST(TaggedCsvLineEnds, PositionsCountedWithCrlfOnAnLfFileAreDetectedAndUsed) {
  const auto c = counters_from(5000, 3000);
  for (bool file_crlf : {false, true}) {
    const TaggedFiles f = tagged(file_crlf ? "crlf_stored" : "lf_stored", c, file_crlf, true);
    TaggedImuCsvReport rep;
    read_tagged_imu_csv(f.csv, f.tag, {}, &rep);
    EXPECT_NEAR(rep.host_rate_error_ppm, 0.0, 50.0) << rep.line_ends;
    EXPECT_EQ(rep.line_ends.rfind(file_crlf ? "as stored" : "CRLF", 0), 0u) << rep.line_ends;
    EXPECT_NEAR(rep.min_latency_s, 0.0, 1e-9);
  }
  const TaggedFiles lf = tagged("lf_lf", c, false, false);
  TaggedImuCsvReport rep;
  read_tagged_imu_csv(lf.csv, lf.tag, {}, &rep);
  EXPECT_EQ(rep.line_ends, "as stored");
  EXPECT_NEAR(rep.host_rate_error_ppm, 0.0, 50.0);
}

// Defect 8: write errors were ignored.
TEST(WriteErrors, AFullDiskIsAnErrorNamingTheFile) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  NavRecord r;
  r.pos = {0.5, 1.0, 10.0};
  EXPECT_NE(error_of([&] {
              NavWriter w("/dev/full");
              w.write(r);
              w.close();
            }).find("/dev/full: "),
            std::string::npos);
  std::vector<ImuIncrement> imu(10);
  EXPECT_NE(error_of([&] { write_kfgins_imu("/dev/full", imu); }).find("/dev/full: "), std::string::npos);
  std::vector<GnssFix> gnss(3);
  EXPECT_NE(error_of([&] { write_kfgins_gnss("/dev/full", gnss, true); }).find("/dev/full"), std::string::npos);
  EXPECT_NE(error_of([&] { save_kfgins_config(KfGinsConfig{}, "/dev/full"); }).find("/dev/full"), std::string::npos);
  EXPECT_NE(error_of([&] {
              OutputFile f("/dev/full");
              f.write("x", 1);
              f.close();
            }).find("/dev/full"),
            std::string::npos);
}

// Issue 35, items 13, 14, 27, 29 (the KF-GINS text readers).
namespace {
std::string gnss_line(double t_s) {
  char b[160];
  std::snprintf(b, sizeof b, "%.3f 30.500000000 114.300000000 20.000 0.010 0.010 0.020\n", t_s);
  return b;
}
}  // namespace

TEST(KfGinsImuCutLine, GivenALastLineCutMidNumberWithoutANewline_ThenItIsDroppedAsCut) {
  // Given: 100 rows written with 9 decimals, the last one cut after "-4." (a recorder killed while writing).
  std::string text;
  char b[200];
  for (int i = 0; i < 100; ++i) {
    std::snprintf(b, sizeof b, "%.4f 0.000100000 0.000200000 0.000300000 0.010000000 0.020000000 -4.123456789\n",
                  100.0 + 0.01 * i);
    text += b;
  }
  text += "101.0000 0.000100000 0.000200000 0.000300000 0.010000000 0.020000000 -4.";
  const std::string p = write_temp("imu_cut.txt", text);
  // When
  ImuReadReport rep;
  const auto imu = read_kfgins_imu(p, &rep);
  // Then: the cut row is dropped and counted; a last row written whole but without a newline is kept.
  EXPECT_EQ(imu.size(), 100u);
  EXPECT_EQ(rep.dropped[DropReason::kMalformed], 1);
  EXPECT_NEAR(imu.back().dvel_b_mps.z(), -4.123456789, 1e-12);
  std::string whole = text.substr(0, text.rfind('\n') + 1) +
                      "101.0000 0.000100000 0.000200000 0.000300000 0.010000000 0.020000000 -4.000000000";
  const auto kept = read_kfgins_imu(write_temp("imu_whole.txt", whole));
  EXPECT_EQ(kept.size(), 101u);
}

TEST(KfGinsGnssTime, GivenOneBadDigitInOneTime_ThenThatFixIsDroppedAsAJumpAndTheFileIsRead) {
  // Given: 121 fixes at 1 Hz, the time of line 52 with a bad digit (345650 -> 945650).
  std::string text;
  for (int i = 0; i < 121; ++i) text += gnss_line(i == 51 ? 945650.0 : 345599.0 + i);
  ASSERT_NE(text.find("945650.000"), std::string::npos);
  const std::string p = write_temp("gnss_digit.txt", text);
  // When
  GnssReadReport rep;
  const auto gnss = read_kfgins_gnss(p, &rep);
  // Then
  EXPECT_EQ(gnss.size(), 120u);
  EXPECT_EQ(rep.dropped[DropReason::kTimeJump], 1);
  EXPECT_EQ(rep.dropped.total(), 1);
  EXPECT_NE(rep.dropped.first[static_cast<int>(DropReason::kTimeJump)].find(":52:"), std::string::npos)
      << rep.dropped.first[static_cast<int>(DropReason::kTimeJump)];
  for (size_t i = 1; i < gnss.size(); ++i) ASSERT_GT(gnss[i].t_s, gnss[i - 1].t_s);
}

TEST(KfGinsImuTime, GivenAStampOneMillisecondBackwards_ThenTheBadLineIsDroppedAndTheGoodOneBeforeItKept) {
  // Given: 200 Hz; line 5002 stamped 1 ms before line 5001 (still after line 5000).
  std::string text;
  for (int i = 0; i < 10000; ++i) text += imu_line(i == 5001 ? 100.0 + 0.005 * 5000 - 0.001 : 100.0 + 0.005 * i);
  const std::string p = write_temp("imu_back_1ms.txt", text);
  ImuReadReport rep;
  const auto imu = read_kfgins_imu(p, &rep);
  EXPECT_EQ(imu.size(), 9999u);
  EXPECT_EQ(rep.dropped[DropReason::kTimeBackwards], 1);
  EXPECT_NE(rep.dropped.first[static_cast<int>(DropReason::kTimeBackwards)].find(":5002:"), std::string::npos)
      << rep.dropped.first[static_cast<int>(DropReason::kTimeBackwards)];
  EXPECT_NEAR(imu[5000].t_s, 100.0 + 0.005 * 5000, 1e-9) << "the good line 5001 is kept";
}

TEST(KfGinsImuTime, GivenTwoStampsNanosecondsApart_ThenTheSecondIsARepeatAndTimesStrictlyIncrease) {
  for (const double apart_s : {3e-9, 1e-8}) {
    std::string text;
    char b[64];
    std::snprintf(b, sizeof b, "%.9f", 100.0 + apart_s);
    text += imu_line(100.0);
    text += std::string(b) + " 0.001 0.001 0.001 0.001 0.001 0.001\n";
    text += imu_file(100, 100.005, 0.005);
    ImuReadReport rep;
    const auto imu = read_kfgins_imu(write_temp("imu_ns.txt", text), &rep);
    EXPECT_EQ(imu.size(), 101u);
    EXPECT_EQ(rep.dropped[DropReason::kRepeated], 1);
    for (size_t i = 1; i < imu.size(); ++i) ASSERT_GT(imu[i].t_s - imu[i - 1].t_s, 1e-5);
  }
}

// Issue 35, item 17: a NaN in the tag header's fraction gave an IMU span "nan - nan" and an error blaming the .pos.
TEST(RtklibTimeTagFile, GivenANanOrOutOfRangeFractionInTheHeader_ThenTheTagFileIsRefusedByName) {
  for (const double fraction : {std::nan(""), 1.5, -0.1, std::numeric_limits<double>::infinity()}) {
    std::string tag = "TIMETAG RTKLIB EX";
    tag.resize(60, '\0');
    put_u32(tag, 0);
    put_u32(tag, static_cast<uint32_t>(kGpsEpochInUnixSeconds + 1000.0));
    tag.append(reinterpret_cast<const char*>(&fraction), 8);
    put_u32(tag, 100);
    put_u32(tag, 10);
    const std::string p = write_temp("nan_fraction.tag", tag);
    const std::string e = error_of([&] { read_rtklib_time_tag(p); });
    EXPECT_NE(e.find(p + ": time-tag header: the start time's fraction"), std::string::npos) << e;
  }
}

// Issue 35, items 20-24, 28, 31 (the KF-GINS configuration): every bad value is refused naming the file, the line
// and the user's own key, never silently taken, and never reported as another part's error.
namespace {
std::string kfgins_text(const std::string& extra) {
  return "imupath: imu.txt\ngnsspath: gnss.txt\nimudatalen: 7\nimudatarate: 200\n"
         "initpos: [30.5, 114.3, 20.0]\ninitvel: [0, 0, 0]\ninitatt: [0, 0, 90]\n"
         "imunoise:\n  arw: [0.2, 0.2, 0.2]\n  vrw: [0.4, 0.4, 0.4]\n  gbstd: [50, 50, 50]\n"
         "  abstd: [250, 250, 250]\n  corrtime: 1.0\n" +
         extra;
}
std::string config_error(const std::string& extra) {
  // A file of its own per case and process: ctest runs each test case as its own process, in parallel.
  const std::string p = write_temp("cfg_" + std::to_string(::getpid()) + "_" +
                                       std::to_string(std::hash<std::string>{}(extra)) + ".yaml",
                                   kfgins_text(extra));
  return error_of([&] { load_kfgins_config(p); });
}
}  // namespace

TEST(KfGinsConfigSchema, GivenTheBaseConfig_ThenItLoads) { EXPECT_EQ(config_error(""), ""); }

TEST(KfGinsConfigSchema, GivenADuplicateKey_ThenBothLinesAreNamed) {
  EXPECT_NE(config_error("imupath: /nonexistent\n").find(":14: imupath: given twice (first at line 1)"),
            std::string::npos)
      << config_error("imupath: /nonexistent\n");
  EXPECT_NE(config_error("ldv:\n  week: 2300\n  week: 2301\n").find(":16: week: given twice (first at line 15)"),
            std::string::npos);
}

TEST(KfGinsConfigSchema, GivenASectionOfTheWrongType_ThenTheErrorNamesTheFileAndTheSection) {
  for (const std::string v : {"[1, 2, 3]", "hello", "5"})
    EXPECT_NE(config_error("ldv: " + v + "\n").find(".yaml:14: key 'ldv': expected a section of keys"),
              std::string::npos)
        << config_error("ldv: " + v + "\n");
  const std::string p = write_temp("cfg_noise.yaml", "imupath: a\ngnsspath: b\nimunoise: 5\n");
  EXPECT_NE(error_of([&] { load_kfgins_config(p); }).find("cfg_noise.yaml:3: key 'imunoise': expected a section"),
            std::string::npos)
      << error_of([&] { load_kfgins_config(p); });
}

TEST(KfGinsConfigSchema, GivenNanOrAbsurdNumbers_ThenTheUsersKeyIsNamed) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"ldv:\n  pos_height_offset_m: .nan\n", "key 'ldv.pos_height_offset_m': expected a finite number"},
      {"ldv:\n  imu_time_shift_s: .nan\n", "key 'ldv.imu_time_shift_s'"},
      {"ldv:\n  imu_time_shift_s: 1e9\n", "key 'ldv.imu_time_shift_s': expected a finite number in [-10, 10] s"},
      {"ldv:\n  week: -5\n", "key 'ldv.week'"},
      {"ldv:\n  week: 99999\n", "key 'ldv.week'"},
      {"starttime: .nan\n", "key 'starttime': expected a finite number"},
      {"endtime: .nan\n", "key 'endtime'"},
      {"imudatarate: .nan\n", "key 'imudatarate'"},
      {"imudatalen: 1e300\n", "key 'imudatalen': expected a finite number in [7, 64] columns, found '1e300'"},
  };
  for (const auto& [extra, expected] : cases) {
    // The later key wins here only because the base text has no such key (else it is a duplicate, refused).
    std::string text = kfgins_text("");
    const std::string key = extra.substr(0, extra.find(':'));
    if (key == "imudatarate" || key == "imudatalen") {
      const size_t at = text.find(key + ":");
      text.erase(at, text.find('\n', at) - at + 1);
    }
    const std::string p = write_temp("cfg_nan.yaml", text + extra);
    const std::string e = error_of([&] { load_kfgins_config(p); });
    EXPECT_NE(e.find(expected), std::string::npos) << extra << " -> " << e;
  }
}

TEST(KfGinsConfigSchema, GivenAnInitialStateOrNoiseBeyondAnySensor_ThenTheKeyIsNamed) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"initatt: [1e300, 0, 15]", "key 'initatt': expected a list of 3 finite numbers, element 1 in [-180, 180] deg"},
      {"initatt: [0, 0, .inf]", "key 'initatt'"},
      {"initpos: [.nan, 114.3, 20]", "key 'initpos'"},
      {"initpos: [100, 114.3, 20]", "key 'initpos': expected a list of 3 finite numbers, element 1 in [-90, 90]"},
      {"initpos: [30, 1e6, 20]", "key 'initpos'"},
      {"imunoise:\n  arw: [0.2, 0.2, 0.2]\n  vrw: [0.4, 0.4, 0.4]\n  gbstd: [1e308, 50, 50]\n"
       "  abstd: [250, 250, 250]\n  corrtime: 1.0",
       "key 'imunoise.gbstd'"},
      {"imunoise:\n  arw: [0.2, 0.2, 0.2]\n  vrw: [0.4, 0.4, 0.4]\n  gbstd: [50, 50, 50]\n"
       "  abstd: [1e308, 250, 250]\n  corrtime: 1.0",
       "key 'imunoise.abstd'"},
      {"imunoise:\n  arw: [0.2, 0.2, 0.2]\n  vrw: [0.4, 0.4, 0.4]\n  gbstd: [50, 50, 50]\n"
       "  abstd: [250, 250, 250]\n  corrtime: 1e300",
       "key 'imunoise.corrtime'"},
      {"initposstd: [1e308, 1, 1]", "key 'initposstd'"},
  };
  for (const auto& [replacement, expected] : cases) {
    std::string text = kfgins_text("");
    const std::string key = replacement.substr(0, replacement.find(':'));
    const size_t at = text.find(key + ":");
    if (at != std::string::npos) {
      size_t end = text.find('\n', at) + 1;
      if (key == "imunoise") end = text.size();  // the section runs to the end of the base text
      text.erase(at, end - at);
    }
    const std::string p = write_temp("cfg_state.yaml", text + replacement + "\n");
    const std::string e = error_of([&] { load_kfgins_config(p); });
    EXPECT_NE(e.find(expected), std::string::npos) << replacement << " -> " << e;
  }
}

// Found by the fuzzer (tests/fuzz/corpus/fuzz_rtklib_files/finding_tagged_csv_week_end): a tagged CSV whose samples
// cross the end of a GPS week went back by 604800 s there (each sample got the seconds of its own week).
TEST(TaggedCsvWeekEnd, GivenSamplesAcrossTheEndOfAGpsWeek_ThenTimesGoOnPastTheWeek) {
  std::string csv, tag = "TIMETAG RTKLIB EX";
  tag.resize(60, '\0');
  put_u32(tag, 0);
  const double week_end_unix_s = kGpsEpochInUnixSeconds + 2300.0 * kSecondsPerWeek + kSecondsPerWeek;
  put_u32(tag, static_cast<uint32_t>(week_end_unix_s - 1.0));  // the log starts 1 s before the week ends
  const double fraction = 0.0;
  tag.append(reinterpret_cast<const char*>(&fraction), 8);
  for (int i = 0; i < 300; ++i) {  // 3 s at 100 Hz
    csv += "0.0,0.0,1.0,0.0,0.0,0.0," + std::to_string(10 * i) + "\n";
    put_u32(tag, static_cast<uint32_t>(10 * i + 3));
    put_u32(tag, static_cast<uint32_t>(csv.size()));
  }
  const auto imu = read_tagged_imu_csv(write_temp("week_end.csv", csv), write_temp("week_end.csv.tag", tag));
  ASSERT_GT(imu.size(), 250u);
  for (size_t i = 1; i < imu.size(); ++i) ASSERT_GT(imu[i].t_s, imu[i - 1].t_s) << i;
  EXPECT_LT(imu.front().t_s, kSecondsPerWeek);
  EXPECT_GT(imu.back().t_s, kSecondsPerWeek) << "seconds of the first week, on past its end";
}

namespace ldv {
// A libFuzzer finding (issue 46, the fuzzer in CI; corpus/fuzz_yaml_configs/finding_path_too_long): a data path
// longer than the system can look up threw "filesystem error: status: File name too long", naming no file. The
// path stays as given, and reading it names it.
TEST(KfGinsConfigSchema, GivenADataPathTooLongToLookUp_ThenTheConfigLoadsAndReadingItNamesThePath) {
  const std::string long_name(5000, 'x');
  const std::string p =
      write_temp("cfg_long_path_" + std::to_string(::getpid()) + ".yaml",
                 "imupath: " + long_name +
                     "\ngnsspath: gnss.txt\nimudatalen: 7\n"
                     "imunoise:\n  arw: [0.2, 0.2, 0.2]\n  vrw: [0.4, 0.4, 0.4]\n  gbstd: [50, 50, 50]\n"
                     "  abstd: [250, 250, 250]\n  corrtime: 1.0\n");
  KfGinsConfig c;
  EXPECT_NO_THROW(c = load_kfgins_config(p));
  EXPECT_EQ(c.imu_path, long_name);
  const std::string e = error_of([&] { read_kfgins_imu(c.imu_path); });
  EXPECT_NE(e.find(long_name.substr(0, 100)), std::string::npos) << e.substr(0, 200);
}
}  // namespace ldv

namespace ldv {
// A libFuzzer finding in the CI's first 15 s runs (corpus/fuzz_yaml_configs/finding_list_as_key): a list in a
// key's place threw yaml-cpp's "bad conversion", naming no file. It is refused naming the file and line.
TEST(KfGinsConfigSchema, GivenAListInAKeysPlace_ThenTheFileAndLineAreNamed) {
  const std::string e = config_error("[3, 3, 3]: 1\n");
  EXPECT_NE(e.find(".yaml:14: expected a key name, found a list"), std::string::npos) << e;  // the last line
}
}  // namespace ldv

namespace ldv {
// Issue 46 (6): a .nav whose time goes back was refused by "navigation series: time goes backwards", naming no file
// or line (ldv compare, report, outage --truth). The reader names both.
TEST(NavFileReader, GivenATimeThatGoesBack_ThenTheFileAndLineAreNamed) {
  std::string text;
  for (int i = 0; i < 10; ++i) {
    const double sow = i == 6 ? 100.0 : 100.0 + i;  // line 7 steps back to the first epoch
    text += "2300 " + std::to_string(sow) + " 30.0 114.0 20.0 0 0 0 0 0 0\n";
  }
  const std::string p = write_temp("back.nav", text);
  const std::string e = error_of([&] { read_nav(p); });
  EXPECT_NE(e.find("back.nav:7: time goes backwards"), std::string::npos) << e;
}
}  // namespace ldv
