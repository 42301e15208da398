// The land-vehicle aids against simulated truth: a car (the simulator moves the vehicle along its body x,
// IMU axes = vehicle axes, so the non-holonomic constraint holds exactly) with 60 s GNSS outages during
// the drive's manoeuvres. The aids must bound the free-inertial drift: the non-holonomic constraint at
// least 3x against no aid for a MEMS IMU (heading and along-track errors remain), odometer + NHC at least
// 10x (the along-track velocity is measured too); the filter's covariance must stay consistent with the
// errors (NEES while aided). The odometer readings are made here from the truth (forward speed + white
// noise), independently of the estimator.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "estimator/run/run_navigation.hpp"
#include "estimator/update/odometer.hpp"
#include "sim/simulator.hpp"
#include "sim_run.hpp"

namespace ldv::est {
namespace {

sim::SimResult land_drive(const std::string& grade, uint64_t seed) {
  sim::SimRequest req;
  req.grade = grade;
  req.seed = seed;
  req.duration_s = 480.0;
  req.gnss_rate_hz = 1.0;
  req.outages = {{200.0, 60.0}, {360.0, 60.0}};
  return sim::simulate(req);
}

// 50 Hz forward speeds of the truth, with 2 cm/s white noise.
std::vector<ObservationPtr> odometer_from_truth(const sim::SimResult& s, uint64_t seed) {
  std::mt19937_64 rng(seed * 7919 + 17);
  std::normal_distribution<double> noise(0.0, 0.02);
  std::vector<ObservationPtr> out;
  const size_t step = static_cast<size_t>(std::lround(s.request.imu_rate_hz / 50.0));
  for (size_t k = 0; k < s.truth.size(); k += step) {
    const sim::TruthSample& t = s.truth[k];
    const double forward = (C_b_n_from_euler(t.rpy_rad).transpose() * t.vel_n_mps).x();
    out.push_back(std::make_shared<OdometerObservation>(t.t_s, forward + noise(rng)));
  }
  return out;
}

struct Drifts {
  double none = 0, nhc = 0, nhc_odo = 0;
};

Drifts mean_drift(const std::string& grade, const std::vector<uint64_t>& seeds) {
  Drifts mean;
  for (uint64_t seed : seeds) {
    const sim::SimResult s = land_drive(grade, seed);
    FilterOptions o = options_from_kfgins(s.kfgins);
    const test::Accuracy none = test::evaluate(s, o);
    o.aids.enabled = {"nhc"};
    const test::Accuracy nhc = test::evaluate(s, o);
    o.aids.enabled = {"nhc", "odometer"};
    const test::Accuracy both = test::evaluate(s, o, 60.0, odometer_from_truth(s, seed));
    std::printf(
        "%s seed %llu: largest outage drift none %.2f m, nhc %.2f m, nhc+odometer %.2f m; "
        "NEES pos/vel/att without aids %.2f %.2f %.2f, with nhc+odometer %.2f %.2f %.2f, gate rejections %ld\n",
        grade.c_str(), static_cast<unsigned long long>(seed), none.outage_drift_m, nhc.outage_drift_m,
        both.outage_drift_m, none.nees_pos, none.nees_vel, none.nees_att, both.nees_pos, both.nees_vel, both.nees_att,
        both.gate_rejections);
    EXPECT_LT(both.nees_pos, 3.0 * 3.0) << "position NEES (3 expected)";
    EXPECT_LT(both.nees_vel, 3.0 * 3.0) << "velocity NEES (3 expected)";
    EXPECT_LT(both.outage_drift_m, 3.0 * both.outage_drift_sigma_m + 0.5) << "drift within the filter's 3 sigma";
    mean.none += none.outage_drift_m / seeds.size();
    mean.nhc += nhc.outage_drift_m / seeds.size();
    mean.nhc_odo += both.outage_drift_m / seeds.size();
  }
  std::printf("%s mean over %zu seeds: none %.2f m, nhc %.2f m (%.1fx), nhc+odometer %.2f m (%.1fx)\n", grade.c_str(),
              seeds.size(), mean.none, mean.nhc, mean.none / mean.nhc, mean.nhc_odo, mean.none / mean.nhc_odo);
  return mean;
}

TEST(LandAids, MemsOutageDriftFallsThreeTimesWithNhcAndTenTimesWithOdometer) {
  const Drifts d = mean_drift("3dm-gx2-typical", {21, 22, 23});
  EXPECT_GT(d.none / d.nhc, 3.0);
  EXPECT_GT(d.none / d.nhc_odo, 10.0);
}

TEST(LandAids, TacticalOutageDriftFallsWithTheAids) {
  const Drifts d = mean_drift("hg1700-typical", {24, 25});
  EXPECT_LT(d.nhc, d.none);
  EXPECT_LT(d.nhc_odo, d.nhc);
}

}  // namespace
}  // namespace ldv::est
