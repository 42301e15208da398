// Allan to filter, end to end (issue 14): a static record of a simulated sensor -> the Allan noise fit ->
// the configuration `ldv allan --noise-config` writes -> the filter on a drive of the same sensor with GNSS
// outages. Against simulated truth: the filter with the identified noise is as consistent as with the
// sensor's true terms (NEES aided, the drift inside the outages against the filter's own sigma), for
// kfgins21 (one Gauss-Markov bias, K folded in) and geoldv51 (its moving bias per term).
#include <gtest/gtest.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <tuple>

#include "common/formats/kfgins_config.hpp"
#include "estimator/run/run_navigation.hpp"
#include "sim/simulator.hpp"
#include "sim_run.hpp"
#include "toolbox/allan/allan_report.hpp"
#include "toolbox/allan/analysis.hpp"

namespace ldv::est {
namespace {

namespace fs = std::filesystem;

// The drive's configuration with the noise the Allan fit identified in place of the true one.
KfGinsConfig config_with_noise(const fs::path& dir, const std::string& noise_yaml) {
  YAML::Node cfg = YAML::LoadFile((dir / "kfgins.yaml").string());
  const YAML::Node noise = YAML::Load(noise_yaml);
  for (const auto& kv : noise["imunoise"]) cfg["imunoise"][kv.first.as<std::string>()] = kv.second;
  for (const auto& kv : noise["ldv"]) cfg["ldv"][kv.first.as<std::string>()] = kv.second;
  YAML::Emitter e;
  e << cfg;
  const fs::path path = dir / "allan_noise.yaml";
  std::ofstream(path) << e.c_str() << "\n";
  return load_kfgins_config(path.string());
}

TEST(AllanToFilter, TheIdentifiedNoiseKeepsTheFilterAsConsistentAsTheTrueTerms) {
  // The stand-in MEMS sensor (3dm-gx2-typical: Q, N, Gauss-Markov B with 300 s, K and a ramp on every axis); a
  // 2 h static record at 50 Hz: the Gauss-Markov's 300 s seen 24 times over.
  sim::SimRequest still;
  still.grade = "3dm-gx2-typical";
  still.scenario = "static";
  still.duration_s = 7200.0;
  still.imu_rate_hz = 50.0;
  still.seed = 41;
  const sim::SimResult record = sim::simulate(still);
  allan::AnalysisOptions opt;
  const std::vector<allan::ChannelResult> fits = allan::analyze(test::allan_channels_of(record), opt, nullptr);
  const std::string noise_yaml = allan::kfgins_noise_yaml(fits);
  ASSERT_FALSE(noise_yaml.empty());
  std::printf("%s", noise_yaml.c_str());

  sim::SimRequest drive;
  drive.grade = "3dm-gx2-typical";
  drive.scenario = "drive";
  drive.duration_s = 600.0;
  drive.gnss_rate_hz = 1.0;
  drive.seed = 42;
  drive.outages = {{200.0, 30.0}, {400.0, 30.0}};
  sim::SimResult run = sim::simulate(drive);
  const fs::path dir = fs::temp_directory_path() / ("ldv_allan_to_filter_" + std::to_string(::getpid()));
  sim::write_outputs(run, dir.string());
  const KfGinsConfig identified = config_with_noise(dir, noise_yaml);
  fs::remove_all(dir);

  for (const std::string model : {"kfgins21", "geoldv51"}) {
    SCOPED_TRACE(model);
    FilterOptions truth_terms = options_from_kfgins(run.kfgins), allan_terms = options_from_kfgins(identified);
    truth_terms.model = allan_terms.model = model;
    const test::Accuracy t = test::evaluate(run, truth_terms), a = test::evaluate(run, allan_terms);
    std::printf(
        "[ info ] %s NEES pos/vel/att: true terms %.2f %.2f %.2f, Allan's %.2f %.2f %.2f; largest outage drift "
        "%.2f m (sigma %.2f), Allan's %.2f m (sigma %.2f)\n",
        model.c_str(), t.nees_pos, t.nees_vel, t.nees_att, a.nees_pos, a.nees_vel, a.nees_att, t.outage_drift_m,
        t.outage_drift_sigma_m, a.outage_drift_m, a.outage_drift_sigma_m);
    // Consistent: the mean NEES (3 dof) inside [3/4, 3 x 3] where the true terms are, and the drift inside
    // the outages within 3 sigma of what the filter says.
    for (const auto& [allan_nees, true_nees, what] :
         {std::tuple{a.nees_pos, t.nees_pos, "position"}, std::tuple{a.nees_vel, t.nees_vel, "velocity"},
          std::tuple{a.nees_att, t.nees_att, "attitude"}}) {
      EXPECT_LT(allan_nees, std::max(9.0, 1.5 * true_nees)) << what;
      EXPECT_GT(allan_nees, std::min(0.75, 0.5 * true_nees)) << what;
    }
    EXPECT_LT(a.outage_drift_m, 3.0 * a.outage_drift_sigma_m);
    EXPECT_LT(a.outage_drift_m, 1.5 * t.outage_drift_m + 0.5) << "the identified model drifts like the true one";
  }
}

}  // namespace
}  // namespace ldv::est
