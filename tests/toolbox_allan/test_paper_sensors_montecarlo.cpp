// Issue 14's study at the paper's record lengths (LABEL montecarlo, about 22 min on 2 cores): 20 seeds of each
// of the paper's sensors (Tables 4-9 as the built-in grades), 16 h at 100 Hz for the HG1700 and HG1900, 5 h at
// 20 Hz for the 3DM-GX2 (both readings of its gyro Q). `ldv allan`'s default analysis (bias model by AIC) and
// the paper's forced Gauss-Markov, each judged by the criteria: Q and N within 3 %, GM sigma and T
// within 20 %, K and R within 30 % where the record's Cramer-Rao bound allows it (else printed), the truth inside
// the 95 % interval, terms the paper did not identify never resolved; and all intervals of an analysis pooled
// inside in 92-99 % (calibrated). The "90 % of seeds" of each tally is judged as a test at 20 seeds
// (expect_paper_criteria_tested: a calibrated interval misses that bar in some 16 of 200 tallies by chance);
// each tally under it is printed with its binomial tail. The short version:
// test_paper_sensors.cpp. Another set of seeds: LDV_PAPER_STUDY_SEEDS=FIRST:COUNT (e.g. 21:40, the 40 more seeds
// of docs/paper_allan_montecarlo.md, "This check").
#include <cstdlib>
#include <optional>
#include <sstream>

#include "tests/toolbox_allan/paper_sensor_study.hpp"

using namespace ldv::allan::test;

namespace {

struct SeedRange {
  int first = 1, count = 20;
};

std::optional<SeedRange> study_seeds() {
  const char* text = std::getenv("LDV_PAPER_STUDY_SEEDS");
  if (text == nullptr) return SeedRange{};
  SeedRange r;
  char colon = 0;
  std::istringstream in(text);
  if (!(in >> r.first >> colon >> r.count) || colon != ':' || r.first < 1 || r.count < 1 || !(in >> std::ws).eof()) {
    ADD_FAILURE() << "LDV_PAPER_STUDY_SEEDS=" << text << ": expected FIRST:COUNT with both at least 1, e.g. 21:40";
    return std::nullopt;
  }
  return r;
}

void judge_paper_study(const std::string& grade, double hours, double rate_hz) {
  const std::optional<SeedRange> seeds = study_seeds();
  if (!seeds) return;
  std::printf("%s: seeds %d to %d\n", grade.c_str(), seeds->first, seeds->first + seeds->count - 1);
  const PaperStudy s = run_paper_study(grade, hours, rate_hz, seeds->count, seeds->first);
  print_study(s, "default (bias model by AIC)", s.by_default);
  print_study(s, "--gauss-markov", s.gauss_markov);
  expect_paper_criteria_tested(s, s.by_default, "default");
  expect_paper_criteria_tested(s, s.gauss_markov, "--gauss-markov");
  expect_pooled_coverage_calibrated(s, s.by_default, "default");
  expect_pooled_coverage_calibrated(s, s.gauss_markov, "--gauss-markov");
}

}  // namespace

TEST(PaperSensorsMonteCarlo, Hg1700SixteenHoursTwentySeeds) { judge_paper_study("hg1700-paper", 16.0, 100.0); }
TEST(PaperSensorsMonteCarlo, Hg1900SixteenHoursTwentySeeds) { judge_paper_study("hg1900-paper", 16.0, 100.0); }
TEST(PaperSensorsMonteCarlo, Gx2FiveHoursTwentySeeds) { judge_paper_study("3dm-gx2-paper", 5.0, 20.0); }
TEST(PaperSensorsMonteCarlo, Gx2QReadAsArcsecFiveHoursTwentySeeds) {
  judge_paper_study("3dm-gx2-paper-q-arcsec", 5.0, 20.0);
}
