// `ldv timesync --imu A --gnss B` (or --kfgins-config C): the clock offset between an IMU and the GNSS track, from
// the turns: the rate the gyros sense about the vertical against the GNSS course's rate
// (estimator/calibrate/imu_latency.hpp), searched over +-max-offset; its sigma from a jackknife over groups of turns. A
// consumer IMU on its own clock, a logger's time column that starts elsewhere: the offset to add to the IMU's times,
// with its sigma, before a run. A or B: a KF-GINS file (imu.txt, gnss.txt), a tagged IMU CSV, an RTKLIB .pos, or a
// configuration (.yaml) whose IMU or GNSS source is taken (ldv.imu_table / ldv.gnss_table included).
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "common/io/input_error.hpp"
#include "estimator/calibrate/drive_imu_latency.hpp"
#include "estimator/calibrate/imu_latency.hpp"
#include "toolbox/assess/nav_inputs.hpp"
#include "tools/ldv/cli_checks.hpp"
#include "tools/ldv/command_registry.hpp"

namespace {
using namespace ldv;

struct TimesyncArgs {
  std::string config, imu, gnss;
  double max_offset_s = 10.0;
  bool json = false;
};

bool has_suffix(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}
bool is_config(const std::string& path) { return has_suffix(path, ".yaml") || has_suffix(path, ".yml"); }

// The drive's IMU and GNSS as `ldv nav` reads them, without its own latency search (what this command measures).
assess::NavInputs load(const std::string& config, const std::string& imu, const std::string& gnss) {
  assess::NavInputArgs a;
  a.config = config;
  a.imu_latency = "off";
  a.refine_latency_in_filter = false;
  a.imu = imu;  // the reader goes by the name: a .csv is a tagged CSV, a .pos an RTKLIB file (input/drive_sources)
  a.gnss = gnss;
  return assess::load_nav_inputs(a);
}

void run_timesync(const TimesyncArgs& t) {
  // A configuration given as --imu or --gnss stands for its source; the other source is the file given, or the
  // same configuration's.
  std::string config = t.config, imu = t.imu, gnss = t.gnss, gnss_config;
  if (is_config(imu)) {
    if (config.empty()) config = imu;
    imu.clear();
  }
  if (is_config(gnss)) {
    gnss_config = gnss;
    gnss.clear();
  }
  const std::string primary = config.empty() ? gnss_config : config;
  if (primary.empty() && (imu.empty() || gnss.empty()))
    throw InputError("ldv timesync", 0,
                     "give --imu A and --gnss B (KF-GINS files, a .pos, or a configuration), or "
                     "--kfgins-config C");
  assess::NavInputs in = load(primary, imu, gnss);
  if (!gnss_config.empty() && gnss_config != primary) in.gnss = load(gnss_config, "", "").gnss;

  est::ImuLatencyOptions o;
  o.max_lag_s = t.max_offset_s;
  o.jackknife_groups = 20;  // the sigma with the course changes' correlation (montecarlo_timesync.cpp)
  const est::ImuLatencyEstimate e = est::estimate_imu_latency(in.imu, in.gnss, o);
  if (!e.valid)
    throw InputError(in.description, 0,
                     "the clock offset cannot be found: " + std::to_string(e.turning_intervals) +
                         " turning GNSS intervals within the IMU's span (at least 20 wanted: a drive with turns, "
                         "overlapping the IMU by more than the search range " +
                         std::to_string(t.max_offset_s) + " s)");
  const double offset_s = -e.lag_s;  // to add to the IMU's times
  // With a configuration (its noise), the filter judges the offset over the whole file: the turns alone read the
  // real walk's hand-held heading lead as 406 ms that the fixes refute.
  const double gain =
      config.empty() ? NAN : est::likelihood_gain_of_lag(in.imu, in.gnss, in.config, in.options, e.lag_s);
  const bool refuted = gain < -est::DriveImuLatency::kLikelihoodTest;
  if (t.json) {
    char judged[96] = "null";
    if (std::isfinite(gain)) std::snprintf(judged, sizeof judged, "%.3f", gain);
    std::printf(
        "{\"tool\":\"ldv timesync\",\"offset_s\":%.6f,\"sigma_s\":%.6f,\"intervals\":%d,\"turning_intervals\":%d,"
        "\"outlier_intervals\":%d,\"residual_rms_rad\":%.6g,\"likelihood_gain\":%s,\"refuted\":%s}\n",
        offset_s, e.sigma_s, e.intervals, e.turning_intervals, e.outlier_intervals, e.residual_rms_rad, judged,
        refuted ? "true" : "false");
    return;
  }
  std::printf(
      "ldv timesync: %zu IMU samples against %zu GNSS fixes (%s): %d GNSS intervals, %d turning, %d left out "
      "as outliers\n",
      in.imu.size(), in.gnss.size(), in.description.c_str(), e.intervals, e.turning_intervals, e.outlier_intervals);
  std::printf("offset_s %.6f +- %.6f\n", offset_s, e.sigma_s);
  std::printf(
      "  add it to the IMU's times: ldv.imu_table's time.offset_s (plus the one there), or ldv.imu_time_shift_s "
      "/ --imu-time-shift for a KF-GINS imu.txt\n");
  if (refuted)
    std::printf(
        "  warning: the GNSS positions fit worse with it (-2 ln L of the fixes rises by %.1f over the whole file, the "
        "filter run with %s): the turns' offset is not one of the clocks (a hand-held unit's heading leads its "
        "track; a lever arm)\n",
        -gain, config.c_str());
  else if (std::isfinite(gain))
    std::printf("  the filter over the whole file: -2 ln L of the GNSS positions %s by %.1f with it\n",
                gain >= 0.0 ? "falls" : "rises", std::abs(gain));
  // An antenna l_x ahead of the IMU turns the track's course as stamps l_x / v late would (behind: early).
  const double lever_along_m = e.equivalent_lever_arm_along_m();
  const double largest_m = est::largest_lever_arm_along_m(in.options);
  if (lever_along_m <= largest_m)
    std::printf(
        "  note: the same turns are what an antenna %.2f m %s the IMU makes at the drive's %.1f m/s (a lever arm "
        "within the %.1f m a vehicle allows): `ldv diagnose` tells the time_offset and lever_arm effects apart\n",
        lever_along_m, offset_s < 0.0 ? "ahead of" : "behind", e.median_speed_mps, largest_m);
}

void add_timesync_command(CLI::App& app) {
  auto a = std::make_shared<TimesyncArgs>();
  CLI::App* c = app.add_subcommand(
      "timesync", "clock offset between an IMU and the GNSS track, from the turns (prints offset_s X +- S)");
  c->add_option("--kfgins-config", a->config, "KF-GINS YAML configuration whose IMU and GNSS sources are compared");
  c->add_option("--imu", a->imu, "IMU: KF-GINS imu.txt, a tagged CSV (.csv + .tag), or a configuration (.yaml)");
  c->add_option("--gnss", a->gnss, "GNSS: KF-GINS gnss.txt, an RTKLIB .pos, or a configuration (.yaml)");
  c->add_option("--max-offset", a->max_offset_s, "search the offset within +- this [s] (default 10)")
      ->check(ldv::cli::finite_range(0.05, 600));
  c->add_flag("--json", a->json, "print JSON");
  c->callback([a] { run_timesync(*a); });
}

const ldv::cli::RegisterCommand kRegisterTimesyncCommand{"timesync", &add_timesync_command};
}  // namespace
