// A fixed-seed fuzz corpus over the file readers: small valid files generated here, then random byte flips,
// truncations, huge numbers, nan/inf, CRLF, binary garbage, repeated / deleted / swapped lines. Each input must
// end in an InputError (a clear message naming the file) or in counted handling whose output is sane (finite,
// time increasing); never a crash, another exception type, or a hang (each input is timed).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>

#include "common/formats/kfgins_config.hpp"
#include "common/formats/kfgins_files.hpp"
#include "common/formats/tagged_imu_csv.hpp"
#include "common/io/input_error.hpp"
#include "common/time/gps_time.hpp"

using namespace ldv;
namespace fs = std::filesystem;

namespace {
constexpr double kMaxSecondsPerInput = 1.0;

std::string temp_path(const std::string& name) { return (fs::temp_directory_path() / ("ldv_fuzz_" + name)).string(); }
void write_file(const std::string& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

std::string valid_imu() {
  std::string s = "# sow dtheta dvel\n";
  char b[200];
  for (int i = 0; i < 200; ++i) {
    std::snprintf(b, sizeof b, "%.6f %.9e %.9e %.9e %.9e %.9e %.9e\n", 1000.0 + 0.005 * i, 1e-5 * i, -2e-5, 3e-6, 0.001,
                  -0.002, -0.049);
    s += b;
  }
  return s;
}
std::string valid_gnss() {
  std::string s;
  char b[200];
  for (int i = 0; i < 50; ++i) {
    std::snprintf(b, sizeof b, "%.3f %.9f %.9f %.4f 0.01 0.02 0.03\n", 1000.0 + i, 30.5 + 1e-6 * i, 114.3, 20.0);
    s += b;
  }
  return s;
}
std::string valid_nav() {
  std::string s;
  char b[300];
  for (int i = 0; i < 50; ++i) {
    std::snprintf(b, sizeof b, "2380 %.6f 30.5 114.3 20.0 0.1 0.2 0.0 1.0 2.0 %.3f\n", 1000.0 + 0.1 * i, 10.0 * i);
    s += b;
  }
  return s;
}
std::string valid_config(const std::string& imu, const std::string& gnss) {
  return "imupath: \"" + imu + "\"\ngnsspath: \"" + gnss +
         "\"\noutputpath: \".\"\nimudatalen: 7\nimudatarate: 200\nstarttime: 1000\nendtime: -1\n"
         "initpos: [30.5, 114.3, 20.0]\ninitvel: [0, 0, 0]\ninitatt: [0, 0, 90]\n"
         "imunoise:\n  arw: [0.2, 0.2, 0.2]\n  vrw: [0.4, 0.4, 0.4]\n  gbstd: [50, 50, 50]\n"
         "  abstd: [250, 250, 250]\n  gsstd: [1000, 1000, 1000]\n  asstd: [1000, 1000, 1000]\n  corrtime: 1.0\n"
         "antlever: [0.1, 0.2, 0.3]\n";
}
// The tagged CSV and its tag file (positions counting the CSV's bytes as written).
void valid_tagged(std::string& csv, std::string& tag) {
  tag = "TIMETAG RTKLIB EX";
  tag.resize(60, '\0');
  const auto put = [&](uint32_t v) { tag.append(reinterpret_cast<const char*>(&v), 4); };
  put(0);
  put(static_cast<uint32_t>(kGpsEpochInUnixSeconds + 1.4e9));
  const double frac = 0.25;
  tag.append(reinterpret_cast<const char*>(&frac), 8);
  csv.clear();
  for (int i = 0; i < 300; ++i) {
    csv += "0.01,-0.02,1.0,0.5,-0.5,0.1," + std::to_string(4294966000u + 7u * static_cast<unsigned>(i)) + "\n";
    put(static_cast<uint32_t>(7 * i + 2));
    put(static_cast<uint32_t>(csv.size() - 1));
  }
}

std::vector<std::string> split_lines(const std::string& s) {
  std::vector<std::string> lines;
  size_t b = 0;
  while (b < s.size()) {
    size_t e = s.find('\n', b);
    if (e == std::string::npos) e = s.size() - 1;
    lines.push_back(s.substr(b, e - b + 1));
    b = e + 1;
  }
  return lines;
}
std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += x;
  return s;
}

std::string mutate(std::string s, std::mt19937_64& rng) {
  static const char* kTokens[] = {"1e308",
                                  "-1e308",
                                  "1e999",
                                  "nan",
                                  "inf",
                                  "-inf",
                                  "45000000000000000000",
                                  "1e-320",
                                  "0x1p3",
                                  "",
                                  "   ",
                                  ",,,",
                                  "18446744073709551615",
                                  "-0",
                                  "1.#INF"};
  const int n_mut = 1 + static_cast<int>(rng() % 3);
  for (int m = 0; m < n_mut && !s.empty(); ++m) {
    const size_t at = rng() % s.size();
    switch (rng() % 10) {
      case 0:
        s[at] = static_cast<char>(rng() % 256);
        break;
      case 1:
        s.resize(at);
        break;
      case 2:
      case 3: {  // a token in place of a field
        size_t b = at;
        while (b > 0 && s[b - 1] != ' ' && s[b - 1] != ',' && s[b - 1] != '\n') --b;
        size_t e = at;
        while (e < s.size() && s[e] != ' ' && s[e] != ',' && s[e] != '\n') ++e;
        s.replace(b, e - b, kTokens[rng() % (sizeof kTokens / sizeof *kTokens)]);
        break;
      }
      case 4: {  // CRLF
        std::string t;
        for (char c : s) t += c == '\n' ? std::string("\r\n") : std::string(1, c);
        s = t;
        break;
      }
      case 5:
      case 6:
      case 7: {  // repeat, delete or swap lines
        auto lines = split_lines(s);
        const size_t i = rng() % lines.size(), j = rng() % lines.size();
        const int op = static_cast<int>(rng() % 3);
        if (op == 0) lines.insert(lines.begin() + static_cast<long>(i), lines[j]);
        if (op == 1) lines.erase(lines.begin() + static_cast<long>(i));
        if (op == 2) std::swap(lines[i], lines[j]);
        s = join(lines);
        break;
      }
      case 8: {  // binary garbage, NULs included
        std::string g(1 + rng() % 64, '\0');
        for (char& c : g) c = static_cast<char>(rng() % 256);
        s.insert(at, g);
        break;
      }
      default:
        s.insert(at, std::string(1 + rng() % 3, "\n\t ,#"[rng() % 5]));
        break;
    }
  }
  return s;
}

// Runs one reader on one input: InputError or a sane result; anything else fails the test with the input saved.
void run_one(const std::string& what, int k, const std::string& input_path, const std::function<void()>& read) {
  const auto t0 = std::chrono::steady_clock::now();
  try {
    read();
  } catch (const InputError& e) {
    EXPECT_FALSE(std::string(e.what()).empty());
  } catch (const std::exception& e) {
    ADD_FAILURE() << what << " input " << k << " (" << input_path << "): not an InputError: " << e.what();
    fs::copy_file(input_path, input_path + ".fail" + std::to_string(k), fs::copy_options::overwrite_existing);
  }
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_LT(s, kMaxSecondsPerInput) << what << " input " << k;
}

void expect_sane(const std::vector<ImuIncrement>& imu) {
  for (size_t i = 0; i < imu.size(); ++i) {
    ASSERT_TRUE(std::isfinite(imu[i].t_s) && std::isfinite(imu[i].dt_s) && imu[i].dtheta_b_rad.allFinite() &&
                imu[i].dvel_b_mps.allFinite());
    if (i > 0) ASSERT_GT(imu[i].t_s, imu[i - 1].t_s);
  }
}

constexpr int kInputsPerReader = 250;
}  // namespace

TEST(ReaderFuzz, KfGinsImu) {
  std::mt19937_64 rng(13);
  const std::string base = valid_imu(), p = temp_path("imu.txt");
  for (int k = 0; k < kInputsPerReader; ++k) {
    write_file(p, mutate(base, rng));
    run_one("imu", k, p, [&] { expect_sane(read_kfgins_imu(p)); });
  }
}

TEST(ReaderFuzz, KfGinsGnssAndNav) {
  std::mt19937_64 rng(14);
  const std::string gnss = valid_gnss(), nav = valid_nav(), pg = temp_path("gnss.txt"), pn = temp_path("sol.nav");
  for (int k = 0; k < kInputsPerReader; ++k) {
    write_file(pg, mutate(gnss, rng));
    run_one("gnss", k, pg, [&] {
      const auto g = read_kfgins_gnss(pg);
      for (size_t i = 1; i < g.size(); ++i) ASSERT_GT(g[i].t_s, g[i - 1].t_s);
    });
    write_file(pn, mutate(nav, rng));
    run_one("nav", k, pn, [&] { read_nav(pn); });
  }
}

TEST(ReaderFuzz, KfGinsConfig) {
  std::mt19937_64 rng(15);
  const std::string base = valid_config("imu.txt", "gnss.txt"), p = temp_path("config.yaml");
  for (int k = 0; k < kInputsPerReader; ++k) {
    write_file(p, mutate(base, rng));
    run_one("config", k, p, [&] { load_kfgins_config(p); });
  }
}

TEST(ReaderFuzz, TaggedImuCsv) {
  std::mt19937_64 rng(16);
  std::string csv, tag;
  valid_tagged(csv, tag);
  const std::string pc = temp_path("imu.csv"), pt = temp_path("imu.csv.tag");
  for (int k = 0; k < kInputsPerReader; ++k) {
    write_file(pc, mutate(csv, rng));
    write_file(pt, k % 5 == 0 ? tag.substr(0, rng() % tag.size()) : tag);
    run_one("tagged csv", k, pc, [&] { expect_sane(read_tagged_imu_csv(pc, pt)); });
  }
}

// The unmutated inputs are read in full (the corpus starts from files the readers accept).
TEST(ReaderFuzz, TheSeedFilesAreValid) {
  const std::string p = temp_path("seed_imu.txt");
  write_file(p, valid_imu());
  EXPECT_EQ(read_kfgins_imu(p).size(), 200u);
  write_file(p, valid_gnss());
  EXPECT_EQ(read_kfgins_gnss(p).size(), 50u);
  write_file(p, valid_nav());
  EXPECT_EQ(read_nav(p).size(), 50u);
  write_file(p, valid_config("imu.txt", "gnss.txt"));
  EXPECT_EQ(load_kfgins_config(p).imu_data_columns, 7);
  std::string csv, tag;
  valid_tagged(csv, tag);
  write_file(p, csv);
  write_file(p + ".tag", tag);
  TaggedImuCsvReport rep;
  EXPECT_EQ(read_tagged_imu_csv(p, p + ".tag", {}, &rep).size(), 299u);
  EXPECT_EQ(rep.counter_wraps, 1);  // 4294966000 + 7 * 299 passes 2^32 = 4294967296
}
