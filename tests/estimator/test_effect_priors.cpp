// ldv.priors (estimator/run/effect_priors_config.hpp, issue 48 item 1): an effect's prior stated in the
// configuration, in its printed unit, is where the filter starts that effect and how sure it is of it; a malformed
// one is refused naming the file, the line and the key.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "common/io/input_error.hpp"
#include "estimator/filter/nav_filter.hpp"
#include "estimator/run/run_navigation.hpp"
#include "estimator/state/state_layout.hpp"
#include "sim/simulator.hpp"
#include "tests/estimator/sim_run.hpp"

namespace ldv::est {
namespace {

namespace fs = std::filesystem;

fs::path config_with(const std::string& ldv_section) {
  const fs::path f = fs::temp_directory_path() / ("ldv_priors_" + std::to_string(::getpid()) + ".yaml");
  std::ofstream(f)
      << "imupath: imu.txt\ngnsspath: gnss.txt\nimunoise:\n  arw: [0.1, 0.1, 0.1]\n  vrw: [0.1, 0.1, 0.1]\n"
      << "  gbstd: [1, 1, 1]\n  abstd: [100, 100, 100]\n  gsstd: [100, 100, 100]\n  asstd: [100, 100, 100]\n"
      << "  corrtime: 1\nldv:\n"
      << ldv_section;
  return f;
}

TEST(EffectPriors, GivenPriorsInTheConfiguration_ThenTheFilterStartsEachEffectFromItsStatedValueAndSigma) {
  const fs::path f = config_with(
      "  add: [g_sensitivity, gyro_misalignment]\n"
      "  priors:\n"
      "    g_sensitivity: {value: [12.0, -3.0, 0.5], sigma: [1.5, 1.0, 2.0], unit: deg/h/g}\n"
      "    gyro_misalignment: {value: [100, -200, 300], sigma: [10, 20, 30]}\n");
  NavFilter filter(options_from_kfgins(load_kfgins_config(f.string())));
  NavState s;
  s.pos = {0.6, 2.0, 100.0};
  s.t_s = 1000.0;
  filter.initialize(s, NavStd{});
  // deg/h/g -> rad/s per m/s^2 and urad -> rad, written out here, not taken from the effect's print unit
  const double deg_h_per_g = (M_PI / 180.0 / 3600.0) / 9.80665;
  const std::map<std::string, std::pair<Vec3, Vec3>> expected = {
      {"g_sensitivity", {Vec3(12.0, -3.0, 0.5) * deg_h_per_g, Vec3(1.5, 1.0, 2.0) * deg_h_per_g}},
      {"gyro_misalignment", {Vec3(100, -200, 300) * 1e-6, Vec3(10, 20, 30) * 1e-6}}};
  int found = 0;
  for (const auto& b : filter.layout().blocks()) {
    const auto it = expected.find(b.effect->name());
    if (it == expected.end()) continue;
    ++found;
    const int o = b.offset - kNavDim;
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(filter.effect_state()(o + i), it->second.first(i), 1e-9 * std::abs(it->second.first(i)))
          << it->first << "[" << i << "]";
      EXPECT_NEAR(std::sqrt(filter.covariance()(b.offset + i, b.offset + i)), it->second.second(i),
                  1e-9 * it->second.second(i))
          << it->first << " sigma [" << i << "]";
    }
  }
  EXPECT_EQ(found, 2);
  fs::remove(f);
}

TEST(EffectPriors, GivenAMalformedPrior_ThenItIsRefusedNamingTheKeyAndLine) {
  const std::pair<const char*, const char*> cases[] = {
      {"    no_such_effect: {value: [1, 2, 3], sigma: [1, 1, 1]}\n", "no such effect"},
      {"    gyro_scale: {value: [1, 2], sigma: [1, 1, 1]}\n", "gyro_scale.value': 2 numbers, expected 3"},
      {"    gyro_scale: {value: [1, 2, 3], sigma: [1, -1, 1]}\n", "gyro_scale.sigma': expected finite numbers >= 0"},
      {"    gyro_scale: {value: [1, 2, 3], sigma: [1, 1, 1], unit: rad}\n", "gyro_scale.unit': 'rad', expected 'ppm'"},
      {"    gyro_scale: {value: [1, .nan, 3], sigma: [1, 1, 1]}\n", "gyro_scale.value': expected finite numbers"},
      {"    gyro_scale: [1, 2, 3]\n", "gyro_scale': expected {value: [...], sigma: [...]}"},
  };
  for (const auto& [entry, why] : cases) {
    const fs::path f = config_with(std::string("  priors:\n") + entry);
    try {
      options_from_kfgins(load_kfgins_config(f.string()));
      ADD_FAILURE() << "accepted: " << entry;
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(why), std::string::npos) << what;
      EXPECT_NE(what.find(f.string() + ":13"), std::string::npos) << "names the file and line 13: " << what;
    }
    fs::remove(f);
  }
}

// Issue 48, item 3: an unknown is not a zero. A user who adds the time offset without stating it (`ldv nav --add
// time_offset`) to an IMU a quarter second late (a USB box stamped on the host): with the prior at 10 ms the lag was
// 25 prior sigmas away, and the filter fought its fixes until the data outweighed the prior (24 rejected, 6
// re-synchronisations); from the default prior (0.3 s, as late as real IMUs come) every fix is used and the lag is
// estimated within 3 sigma.
TEST(EffectPriors, GivenATimeOffsetAddedWithoutAPrior_ThenAQuarterSecondLagIsEstimatedWithinThreeSigma) {
  sim::SimRequest req;
  req.grade = "hg1700-typical";
  req.seed = 27;
  req.duration_s = 300.0;
  req.scenario = "drive";
  req.gnss_rate_hz = 5.0;
  req.effects = {"time_offset=0.25"};
  const sim::SimResult sim = sim::simulate(req);
  FilterOptions o = options_from_kfgins(sim.kfgins);
  o.add = {"time_offset"};
  NavFilter f(o);
  run_navigation(sim.imu, sim.gnss, sim.kfgins, f, RunCallbacks{});
  const StateBlock* b = f.layout().find("time_offset");
  ASSERT_NE(b, nullptr);
  const double estimate_s = f.effect_state()(b->offset - kNavDim);
  const double sigma_s = std::sqrt(f.covariance()(b->offset, b->offset));
  const double truth_s = sim.injected_effects.at("time_offset")[0];
  std::printf("time_offset %.4f +- %.4f s, truth %.3f s; %ld rejections, %ld re-synchronisations\n", estimate_s,
              sigma_s, truth_s, f.faults().gate_rejections, f.faults().gate_resyncs);
  EXPECT_LT(std::abs(estimate_s - truth_s), 3.0 * sigma_s);
  EXPECT_LT(sigma_s, 0.05);  // and the drive did pin it down
  EXPECT_EQ(f.faults().gate_rejections, 0);
}

// An effect added without a stated prior is learnt from the drive (issue 48, items 3 and 4): its default prior is as
// wide as IMUs of any grade make it. Hidden at realistic sizes on drives with two 30 s outages, adding it from that
// prior takes out at least 90 % of the outage drift the effect adds over a run that knows it exactly (the
// tactical defaults, 100 urad, held a MEMS misalignment at zero and removed none of it). Not yet for every effect: a
// MEMS accelerometer misalignment of 7 mrad, added so, takes out half of its drift (34.5 -> 30.2 m, known: 26.3 m;
// its x and y parts couple gravity into the horizontal as a bias does and separate from it on pitch and roll only).
struct HiddenEffectCase {
  const char* grade;
  const char* effect;  // as the simulator injects it, engineering units
  const char* name;
};
double outage_drift_m(const sim::SimResult& sim, FilterOptions o) {
  return test::evaluate(sim, o, 60.0).outage_drift_m;
}

TEST(EffectPriors, GivenAHiddenMisalignmentAddedWithoutAPrior_ThenTheDriveLearnsItAndItsErrorFalls) {
  const HiddenEffectCase cases[] = {
      {"hg1700-typical", "accel_misalignment=475,-400,450", "accel_misalignment"},    // ~2.2 mrad: tactical
      {"3dm-gx2-typical", "gyro_misalignment=1444,-1200,1300", "gyro_misalignment"},  // ~6.5 mrad: consumer MEMS
  };
  for (const HiddenEffectCase& c : cases) {
    SCOPED_TRACE(c.effect);
    sim::SimRequest req;
    req.grade = c.grade;
    req.seed = 21;
    req.duration_s = 900.0;
    req.scenario = "drive";
    req.gnss_rate_hz = 5.0;
    req.outages = {{300.0, 30.0}, {600.0, 30.0}};
    req.effects = {c.effect};
    const sim::SimResult sim = sim::simulate(req);
    const FilterOptions model = options_from_kfgins(sim.kfgins);
    FilterOptions added = model, known = model;
    added.add = known.add = {c.name};
    const std::vector<double>& truth = sim.injected_effects.at(c.name);
    Eigen::VectorXd truth_si(3);
    truth_si << truth[0], truth[1], truth[2];
    known.effect_priors[c.name] = {truth_si, Eigen::VectorXd::Constant(3, 1e-9)};
    const double without = outage_drift_m(sim, model), with = outage_drift_m(sim, added),
                 exact = outage_drift_m(sim, known);
    std::printf(
        "[ info ] %s on %s: largest outage drift %.3f m without it, %.3f m added from the default prior, "
        "%.3f m known\n",
        c.effect, c.grade, without, with, exact);
    ASSERT_GT(without, 1.3 * exact) << "the effect must matter on this drive";
    EXPECT_LT(with - exact, 0.1 * (without - exact));
  }
}

// An effect state's error is what its covariance says (issue 48, item 3): over independent drives with a hidden lever
// arm and GNSS lag added from their default priors, the normalised estimation error squared of the effect states
// (4 dof a drive) averages to 1 per dof within the chi-square band of the draws.
TEST(EffectPriors, GivenHiddenLeverArmsAndLagsAddedFromTheirDefaultPriors_ThenTheirStatesNeesIsInBand) {
  constexpr int kDrives = 10;
  double nees = 0.0;
  int dof = 0;
  for (int seed = 1; seed <= kDrives; ++seed) {
    sim::SimRequest req;
    req.grade = "hg1700-typical";
    req.seed = static_cast<unsigned>(500 + seed);
    req.duration_s = 300.0;
    req.scenario = "drive";
    req.gnss_rate_hz = 5.0;
    const double s = seed % 2 ? 1.0 : -1.0;
    char lever[64], lag[32];
    std::snprintf(lever, sizeof lever, "lever_arm=%.2f,%.2f,%.2f", 1.5 * s, -0.8, -1.2 + 0.1 * seed);
    std::snprintf(lag, sizeof lag, "time_offset=%.3f", 0.02 * seed * s);
    req.effects = {lever, lag};
    const sim::SimResult sim = sim::simulate(req);
    FilterOptions o = options_from_kfgins(sim.kfgins);
    o.add = {"lever_arm", "time_offset"};
    NavFilter f(o);
    run_navigation(sim.imu, sim.gnss, sim.kfgins, f, RunCallbacks{});
    for (const char* name : {"lever_arm", "time_offset"}) {
      const StateBlock* b = f.layout().find(name);
      ASSERT_NE(b, nullptr) << name;
      const std::vector<double>& truth = sim.injected_effects.at(name);
      Eigen::VectorXd e(b->dim);
      for (int k = 0; k < b->dim; ++k) e(k) = f.effect_state()(b->offset - kNavDim + k) - truth[k];
      const Eigen::MatrixXd P = f.covariance().block(b->offset, b->offset, b->dim, b->dim);
      nees += e.dot(P.ldlt().solve(e));
      dof += b->dim;
    }
  }
  // 40 dof: the 95 % chi-square band of the sum is [24.4, 59.3].
  std::printf("[ info ] effect-state NEES %.1f over %d dof (%.2f per dof)\n", nees, dof, nees / dof);
  EXPECT_GT(nees, 24.4);
  EXPECT_LT(nees, 59.3);
}

}  // namespace
}  // namespace ldv::est
