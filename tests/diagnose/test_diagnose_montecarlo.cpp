// Many-seed study (label montecarlo): detection, false alarms and error reduction of `ldv diagnose`
// on simulated drives with exactly one hidden effect, tactical and MEMS grades, large and
// near-threshold sizes. Seeds per case: LDV_DIAG_SEEDS (default 20); LDV_DIAG_SIZE=none|large|near runs only
// the cases of that size (e.g. the false-alarm calibration alone), LDV_DIAG_EFFECT=TEXT those whose effect spec
// contains TEXT. Prints one table.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>

#include "tests/diagnose/trial.hpp"

namespace ldv::diag {
namespace {

int seeds() {
  const char* s = std::getenv("LDV_DIAG_SEEDS");
  return s ? std::max(1, std::atoi(s)) : 20;
}

struct Case {
  std::string grade, effect, model, size;  // size: "large" / "near" / "none"
};

// Sizes (engineering units of `ldv sim --effect`). "large": well above the minimal detectable size
// of a 15-min drive; "near": about 1-2 times it.
const Case kCases[] = {
    {"hg1700-typical", "", "kfgins21", "none"},
    {"3dm-gx2-typical", "", "kfgins21", "none"},
    {"hg1700-typical", "lever_arm=0.5,-0.3,-1.2", "kfgins21", "large"},
    {"hg1700-typical", "lever_arm=0.02,-0.015,0.03", "kfgins21", "near"},
    {"hg1700-typical", "time_offset=0.05", "kfgins21", "large"},
    {"hg1700-typical", "time_offset=0.001", "kfgins21", "near"},
    {"hg1700-typical", "gyro_scale=1500,-1000,2000", "ins15", "large"},
    {"hg1700-typical", "gyro_scale=300,-200,500", "ins15", "near"},
    {"hg1700-typical", "accel_scale=5000,-4000,6000", "ins15", "large"},
    {"hg1700-typical", "gyro_misalignment=400,-300,350", "kfgins21", "large"},
    {"hg1700-typical", "gyro_misalignment=100,-60,80", "kfgins21", "near"},
    {"hg1700-typical", "accel_misalignment=400,-300,350", "kfgins21", "large"},
    {"hg1700-typical", "g_sensitivity=60,-40,20", "kfgins21", "large"},
    {"3dm-gx2-typical", "lever_arm=0.5,-0.3,-1.2", "kfgins21", "large"},
    {"3dm-gx2-typical", "time_offset=0.05", "kfgins21", "large"},
    {"3dm-gx2-typical", "gyro_scale=20000,-15000,25000", "ins15", "large"},
    {"3dm-gx2-typical", "accel_scale=20000,-15000,25000", "ins15", "large"},
    {"3dm-gx2-typical", "gyro_misalignment=2000,-1500,1800", "kfgins21", "large"},
    {"3dm-gx2-typical", "accel_misalignment=2000,-1500,1800", "kfgins21", "large"},
    {"3dm-gx2-typical", "g_sensitivity=600,-400,300", "kfgins21", "large"},
};

}  // namespace

TEST(DiagnoseMonteCarlo, DetectionFalseAlarmsAndErrorReduction) {
  const int n = seeds();
  std::printf("%-8s %-40s %-9s %-5s %6s %6s %7s %7s %8s %8s\n", "grade", "hidden effect", "model", "size", "first",
              "group1", "verdict", "any", "removed", "cpu_s");
  const char* only_size = std::getenv("LDV_DIAG_SIZE");
  const char* only_effect = std::getenv("LDV_DIAG_EFFECT");  // the cases whose effect spec contains it
  for (const Case& c : kCases) {
    if (only_size && c.size != only_size) continue;
    if (only_effect && c.effect.find(only_effect) == std::string::npos) continue;
    int first = 0, group = 0, verdict = 0, any = 0, reductions = 0;
    double removed_min = 1e300, cpu = 0.0;
    const std::string name = c.effect.empty() ? "" : testing::effect_name(c.effect);
    const bool measure_error = c.size == "large" && (name == "lever_arm" || name == "time_offset" || name == "gyro_scale");
    for (int s = 0; s < n; ++s) {
      testing::Trial t{c.grade, c.effect, c.model, static_cast<uint64_t>(1000 + s)};
      const testing::Outcome o = testing::run_trial(t, measure_error);
      first += o.ranked_first;
      group += o.in_first_group;
      verdict += o.verdict_has;
      any += o.verdict_any;
      cpu += o.cpu_s;
      if (measure_error) {
        removed_min = std::min(removed_min, o.excess_removed());
        reductions += o.excess_removed() >= 0.8;
      }
    }
    std::printf("%-8s %-40s %-9s %-5s %5.0f%% %5.0f%% %6.0f%% %6.0f%% %8s %8.2f\n", c.grade.c_str(),
                c.effect.empty() ? "(none)" : c.effect.c_str(), c.model.c_str(), c.size.c_str(), 100.0 * first / n,
                100.0 * group / n, 100.0 * verdict / n, 100.0 * any / n,
                measure_error ? (std::to_string(reductions * 100 / n) + "%>=.8").c_str() : "-", cpu / n);
    std::fflush(stdout);
    if (c.size == "none") {
      EXPECT_LE(any, 0.05 * n) << c.grade << ": false verdicts";
    }
    if (c.size == "large") {
      EXPECT_GE(group, 0.95 * n) << c.grade << " " << c.effect << ": ranked first (or its group)";
    }
    if (measure_error) {
      EXPECT_GE(reductions, 0.95 * n) << c.grade << " " << c.effect << ": excess error removed";
    }
  }
}

}  // namespace ldv::diag
