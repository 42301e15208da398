// Deviations against independent truth: NIST SP 1065's NBS14 values and Stable32's results for
// PHASE.DAT and a real OCXO, every value to the printed digits; Stable32's confidence bounds within 2 %.
#include <gtest/gtest.h>

#include <cstdint>

#include "tests/toolbox_allan/stable32_results.hpp"
#include "toolbox/allan/allan_input.hpp"
#include "toolbox/allan/confidence.hpp"
#include "toolbox/allan/deviation.hpp"
#include "toolbox/allan/edf.hpp"

using namespace ldv::allan;
using namespace ldv::allan::test;

namespace {

// NIST SP 1065 p. 107: the NBS14 1000-point frequency set, from a Lehmer generator.
std::vector<double> nbs14_frequency() {
  std::vector<double> y;
  std::uint64_t n = 1234567890;
  for (int i = 0; i < 1000; ++i) {
    y.push_back(static_cast<double>(n) / 2147483647.0);
    n = (16807 * n) % 2147483647;
  }
  return y;
}

PhaseSeries phase_dat() {
  InputOptions opt;
  opt.format = InputFormat::kPhase;
  return read_allan_input(shared_data("allan/phasedat/PHASE.DAT"), opt).front();
}

PhaseSeries ocxo() {
  InputOptions opt;
  opt.format = InputFormat::kFrequency;
  opt.nominal = 10e6;
  return read_allan_input(shared_data("allan/ocxo/ocxo_frequency.txt"), opt).front();
}

struct Nbs14Case {
  Deviation dev;
  double at1, at10, at100;
};

}  // namespace

TEST(Nbs14, EveryPublishedDeviationToSevenDigits) {
  const PhaseSeries s = phase_from_rates(nbs14_frequency(), 1.0, "nbs14", "1");
  ASSERT_EQ(s.x.size(), 1001u);
  const Nbs14Case cases[] = {
      {Deviation::kAdev, 2.922319e-01, 9.965736e-02, 3.897804e-02},
      {Deviation::kOadev, 2.922319e-01, 9.159953e-02, 3.241343e-02},
      {Deviation::kMdev, 2.922319e-01, 6.172376e-02, 2.170921e-02},
      {Deviation::kHdev, 2.943883e-01, 1.052754e-01, 3.910860e-02},
      {Deviation::kOhdev, 2.943883e-01, 9.581083e-02, 3.237638e-02},
      {Deviation::kTdev, 1.687202e-01, 3.563623e-01, 1.253382e+00},
  };
  for (const auto& c : cases) {
    const auto pts = deviations(s.x, 1.0, c.dev, {1, 10, 100});
    const double want[3] = {c.at1, c.at10, c.at100};
    for (int i = 0; i < 3; ++i) {
      EXPECT_TRUE(matches_printed(pts[i].dev, want[i], 7))
          << deviation_name(c.dev) << " tau " << pts[i].tau_s << ": " << pts[i].dev << " vs " << want[i];
    }
  }
}

class PhaseDat : public ::testing::TestWithParam<std::string> {};

TEST_P(PhaseDat, AllTauAndOctaveMatchStable32) {
  const std::string name = GetParam();
  const Deviation dev = parse_deviation(name);
  const PhaseSeries s = phase_dat();
  int bounds_checked = 0, pipeline_checked = 0;
  for (const std::string suffix : {"", "_octave"}) {
    const auto rows = read_stable32_table(shared_data("allan/phasedat/phase_dat_" + name + suffix + ".txt"));
    ASSERT_GT(rows.size(), 7u);
    std::vector<long> ms;
    for (const auto& r : rows) ms.push_back(r.af);
    const auto pts = stability(s, dev, ms);
    for (size_t i = 0; i < rows.size(); ++i) {
      const auto& r = rows[i];
      const auto& p = pts[i];
      EXPECT_EQ(p.point.n_terms, r.n) << name << suffix << " AF " << r.af;
      EXPECT_TRUE(matches_printed(p.point.dev, r.sigma, 5))
          << name << suffix << " AF " << r.af << ": " << p.point.dev << " vs " << r.sigma;
      if (r.min_sigma > 0) {
        ++bounds_checked;
        // EDF and chi-square with Stable32's noise type: every row within 2 %.
        const double edf = greenhall_edf(dev, r.alpha, r.af, static_cast<long>(s.x.size()));
        const Interval given = chi_square_interval(p.point.dev, edf, kOneSigmaConfidence);
        EXPECT_NEAR(given.lo / r.min_sigma, 1.0, 0.02) << name << " AF " << r.af << " min sigma";
        EXPECT_NEAR(given.hi / r.max_sigma, 1.0, 0.02) << name << " AF " << r.af << " max sigma";
        // The whole pipeline (our own noise identification): wherever it finds Stable32's type. The
        // lag-1 ACF (>= 30 averaged points) must; the B1 ratio on 7 averages (AF 128) differs.
        if (p.alpha_by_acf) {
          EXPECT_EQ(p.alpha, r.alpha) << name << " AF " << r.af << " noise type";
        }
        if (p.alpha == r.alpha) {
          ++pipeline_checked;
          EXPECT_NEAR(p.interval.lo / r.min_sigma, 1.0, 0.02) << name << " AF " << r.af << " min sigma";
          EXPECT_NEAR(p.interval.hi / r.max_sigma, 1.0, 0.02) << name << " AF " << r.af << " max sigma";
        }
      }
    }
  }
  EXPECT_GE(pipeline_checked, 7);
  EXPECT_GE(bounds_checked, 8);
}

INSTANTIATE_TEST_SUITE_P(Stable32, PhaseDat, ::testing::Values("adev", "oadev", "mdev", "hdev", "ohdev", "tdev"));

class Ocxo : public ::testing::TestWithParam<std::string> {};

TEST_P(Ocxo, AllTauMatchStable32) {
  const std::string name = GetParam();
  const Deviation dev = parse_deviation(name);
  static const PhaseSeries s = ocxo();
  const auto rows = read_stable32_table(shared_data("allan/ocxo/stable32_" + name + "_alltau.txt"));
  ASSERT_GT(rows.size(), 200u);
  int alpha_agree = 0, acf_points = 0, acf_agree = 0;
  std::vector<long> ms;
  for (const auto& r : rows) ms.push_back(r.af);
  const auto pts = stability(s, dev, ms);
  for (size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(pts[i].point.n_terms, rows[i].n) << name << " AF " << rows[i].af;
    EXPECT_TRUE(matches_printed(pts[i].point.dev, rows[i].sigma, 5))
        << name << " AF " << rows[i].af << ": " << pts[i].point.dev << " vs " << rows[i].sigma;
    alpha_agree += pts[i].alpha == rows[i].alpha;
    if (pts[i].alpha_by_acf) {
      ++acf_points;
      acf_agree += pts[i].alpha == rows[i].alpha;
    }
  }
  // The lag-1 ACF identification (>= 30 averaged points) is Stable32's and must agree; for fewer
  // points our B1/R(n) path differs from Stable32's in details we could not pin down: report it.
  const double agreement = static_cast<double>(alpha_agree) / rows.size();
  const double acf_agreement = static_cast<double>(acf_agree) / acf_points;
  std::printf("%s: noise type agrees with Stable32 at %.0f %% of %zu taus (lag-1 ACF taus: %.0f %% of %d)\n",
              name.c_str(), 100 * agreement, rows.size(), 100 * acf_agreement, acf_points);
  EXPECT_GE(acf_agreement, 0.95);
}

INSTANTIATE_TEST_SUITE_P(Stable32, Ocxo, ::testing::Values("adev", "oadev", "mdev", "hdev", "ohdev", "tdev"));
