// The smoother's criteria (issue 15) over seeds: tactical (hg1700-typical) and consumer MEMS (3dm-gx2-typical),
// a 60 s and a 120 s GNSS outage in the turns of a figure 8, seeds 1-6 (the default suite runs one seed of each:
// test_rts_smoother.cpp). Label montecarlo: `ctest --test-dir build -L montecarlo -R smoother`.
//
// The share of the forward drift is checked over the seeds (sum of the smoothed maxima over the sum of the forward
// end drifts, per gap length): the forward drift at a gap's end is one draw of a random walk and can end near
// zero by chance (hg1700-typical 60 s gaps: 0.8-4.8 m), while the smoothed error inside a gap has a floor the
// ends cannot remove (the gyro's white noise, 0.125 deg/sqrt(h), tilts the platform by a random walk that both
// ends only pin: ~0.1-0.3 m in 60 s). test_smoother_closed_form.cpp derives that floor in closed form: with
// this white noise alone, about a third of 60 s gaps miss the 1/10 per gap with the optimal smoother. Every
// gap is printed; each seed must also be consistent (3 sigma, NEES).
#include <gtest/gtest.h>

#include <cstdio>
#include <map>

#include "tests/estimator/sim_run.hpp"

namespace ldv::est {
namespace {

void expect_over_seeds(const char* grade, double max_ratio) {
  const std::vector<sim::Outage> gaps = {{120.0, 60.0}, {260.0, 120.0}};
  std::map<double, std::pair<double, double>> sums;  // length -> (smoothed max, forward end)
  int within_own_ratio = 0, total = 0;
  for (int seed = 1; seed <= 6; ++seed) {
    const test::SmoothedDrive d = test::smooth_drive(grade, seed, gaps, 440.0);
    test::expect_smoothed_consistent(d);
    for (std::size_t g = 0; g < gaps.size(); ++g) {
      sums[gaps[g].length_s].first += d.gaps[g].smoothed_max_m;
      sums[gaps[g].length_s].second += d.gaps[g].forward_end_m;
      within_own_ratio += d.gaps[g].smoothed_max_m <= max_ratio * d.gaps[g].forward_end_m;
      ++total;
    }
  }
  for (const auto& [length, s] : sums) {
    std::printf("%s, %.0f s gaps over 6 seeds: smoothed max / forward end drift = %.3f / %.3f m = %.3f\n", grade,
                length, s.first / 6, s.second / 6, s.first / s.second);
    EXPECT_LE(s.first, max_ratio * s.second) << length << " s gaps";
  }
  std::printf("%s: %d of %d gaps within %.2f of their own forward drift\n", grade, within_own_ratio, total, max_ratio);
}

TEST(SmootherSeeds, TacticalSmoothedGapErrorIsATenthOfTheForwardDrift) { expect_over_seeds("hg1700-typical", 0.1); }

TEST(SmootherSeeds, MemsSmoothedGapErrorIsAQuarterOfTheForwardDrift) { expect_over_seeds("3dm-gx2-typical", 0.25); }

}  // namespace
}  // namespace ldv::est
