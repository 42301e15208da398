#include "toolbox/assess/nav_inputs.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "common/formats/imu_calibration.hpp"
#include "common/formats/odometer_text.hpp"
#include "common/io/input_error.hpp"
#include "estimator/calibrate/drive_imu_latency.hpp"
#include "estimator/calibrate/gnss_velocity_check.hpp"
#include "estimator/filter/nav_filter.hpp"
#include "estimator/run/run_navigation.hpp"
#include "estimator/update/odometer.hpp"

namespace ldv::assess {
namespace {

// After the calibration, what is left of the bias and scale errors is its uncertainty: that becomes the
// filter's prior, unless the configuration gives one or the calibration does not know it (a zero sigma).
std::string take_priors_from(const calib::ImuCalibration& cal, const KfGinsConfig& cfg, est::FilterOptions& o) {
  std::string taken;
  const auto take = [&](est::BlockOptions& block, const std::optional<Vec3>& configured, const Vec3& sigma,
                        const char* name) {
    if (configured || !(sigma.array() > 0.0).all()) return false;
    block.init_std = sigma;
    taken += (taken.empty() ? "" : ", ") + std::string(name);
    return true;
  };
  // options_from_kfgins gives the moving bias's constant part the bias prior: keep them together.
  if (take(o.gyro_bias, cfg.init_gyro_bias_std_rad_s, cal.gyro.bias_sigma, "gyro_bias"))
    o.gyro_moving_bias.constant_std = o.gyro_bias.init_std;
  if (take(o.accel_bias, cfg.init_accel_bias_std_mps2, cal.accel.bias_sigma, "accel_bias"))
    o.accel_moving_bias.constant_std = o.accel_bias.init_std;
  take(o.gyro_scale, cfg.init_gyro_scale_std, cal.gyro.scale_sigma, "gyro_scale");
  take(o.accel_scale, cfg.init_accel_scale_std, cal.accel.scale_sigma, "accel_scale");
  return taken;
}

}  // namespace

NavInputs load_nav_model(const NavInputArgs& a) {
  NavInputs in;
  if (!a.config.empty()) {
    in.config = load_kfgins_config(a.config);
    in.options = est::options_from_kfgins(in.config);
  } else {
    in.config.output_path = ".";
  }
  if (a.lever.size() == 3) in.options.lever_arm.init = Vec3(a.lever[0], a.lever[1], a.lever[2]);
  if (a.kfgins_compatible) {  // KF-GINS's update, and its alignment: body x along the course
    est::make_kfgins_compatible(in.options, in.config);
    if (!has_ldv_key(in.config, "align_hypotheses")) in.options.align_hypotheses = 1;
  }
  if (!a.aids.empty()) in.options.aids.enabled = a.aids;
  if (!a.model.empty()) in.options.model = a.model;
  in.options.add.insert(in.options.add.end(), a.add.begin(), a.add.end());
  in.options.drop.insert(in.options.drop.end(), a.drop.begin(), a.drop.end());
  return in;
}

namespace {

// The odometer's readings when the odometer aid is on: --odometer, else ldv.odopath (resolved like imupath).
void load_odometer(const NavInputArgs& a, NavInputs& in) {
  if (!in.options.aids.has("odometer")) return;
  std::string path = a.odometer;
  if (path.empty() && has_ldv_key(in.config, "odopath")) {
    try {
      path = resolve_data_path(in.config.ldv["odopath"].as<std::string>(), in.config.config_path);
    } catch (const YAML::Exception&) {
      throw InputError(in.config.config_path, in.config.ldv["odopath"].Mark().line + 1,
                       "key 'ldv.odopath': expected a path");
    }
  }
  if (path.empty())
    throw InputError(in.config.config_path.empty() ? "--aid odometer" : in.config.config_path, 0,
                     "the odometer aid needs its readings: --odometer FILE or ldv.odopath (lines 'sow speed_mps')");
  const std::vector<OdometerSample> samples = read_odometer_text(path);
  if (samples.empty()) throw InputError(path, 0, "no odometer readings");
  for (const OdometerSample& o : samples)
    in.other_observations.push_back(std::make_shared<est::OdometerObservation>(o.t_s, o.speed_mps));
  in.file_counts.push_back({"odometer", path, static_cast<long>(samples.size()), {}});
  in.description += " + " + path;
}

// GNSS velocities are fused only where they agree with the positions, unless the configuration says
// (ldv.use_gnss_velocity) or KF-GINS's behaviour is asked for.
void decide_gnss_velocity_use(const NavInputArgs& a, NavInputs& in) {
  const bool configured = has_ldv_key(in.config, "use_gnss_velocity");
  const bool any_velocity =
      std::any_of(in.gnss.begin(), in.gnss.end(), [](const GnssFix& f) { return f.has_velocity; });
  const bool kfgins = a.kfgins_compatible || !in.options.robust_update;
  if (configured || kfgins || !any_velocity || !in.options.use_gnss_velocity) return;
  const est::GnssVelocityCheck c = est::check_gnss_velocity(in.gnss);
  in.gnss_velocity_check = c;
  char note[220];
  if (c.consistent()) {
    std::snprintf(note, sizeof note, "GNSS velocity used (agrees with the positions: misfit %.1fx its sigma^2 over %d fixes)",
                  c.normalised_mse, c.compared);
  } else {
    in.options.use_gnss_velocity = false;
    std::snprintf(note, sizeof note,
                  "GNSS velocity not used: misfit %.1fx its stated sigma^2 against the positions over %d fixes "
                  "(best aligned %.0f ms late: %.1fx%s); positions only",
                  c.normalised_mse, c.compared, 1e3 * c.best_lag_s, c.normalised_mse_at_lag,
                  c.lagged() ? ", a significant lag" : "");
  }
  in.gnss_velocity_note = note;
}

}  // namespace

NavInputs load_nav_inputs(const NavInputArgs& a) {
  NavInputs in = load_nav_model(a);
  const auto setting = [&](double given, const char* key) {
    return given != NavInputArgs::kUnset ? given : (a.config.empty() ? 0.0 : est::ldv_number(in.config, key, 0.0));
  };
  const double height_offset_m = setting(a.pos_height_offset_m, "pos_height_offset_m");
  const double float_std_min_m = setting(a.float_std_min_m, "float_std_min_m");
  const double imu_time_shift_s = setting(a.imu_time_shift_s, "imu_time_shift_s");
  // The files, as the configuration names them and the command line overrides them (the one reading of them).
  input::SourceArgs sources;
  sources.imu = a.imu, sources.imu_csv = a.imu_csv, sources.imu_tag = a.imu_tag;
  sources.gnss = a.gnss, sources.rtklib_pos = a.rtklib_pos;
  sources.csv_axes = a.csv_axes;
  sources.calibration = a.calibration;
  sources.pos_height_offset_m = height_offset_m;
  sources.float_std_min_m = float_std_min_m;
  sources.imu_time_shift_s = imu_time_shift_s;
  sources.imu_layout_declared = !a.config.empty();
  input::DriveSources read = input::read_drive_sources(sources, in.config);
  in.imu = std::move(read.imu);
  in.gnss = std::move(read.gnss);
  in.imu_gaps = std::move(read.imu_gaps);
  in.file_counts = std::move(read.counts);
  in.imu_note = read.imu_note;
  in.gnss_note = read.gnss_note;
  in.description = read.description;
  in.gps_week = read.gps_week;
  // The tags' jitter from the rows themselves, where the reader knows them: measured here or not at all (the run
  // would read the reads' scatter in the increments, not the samples').
  if (read.tags.known && in.options.imu_stamp_jitter_from_tags) {
    in.imu_stamp_jitter =
        est::measure_imu_stamp_jitter(read.tags.distinct_sample_tags_s, read.tags.rows, read.tags.repeated_rows);
    if (in.imu_stamp_jitter.found) in.options.imu_stamp_jitter_s = in.imu_stamp_jitter.sigma_s;
    in.options.imu_stamp_jitter_from_tags = false;
  }
  if (read.calibration) {
    const std::string priors = take_priors_from(*read.calibration, in.config, in.options);
    if (!priors.empty()) in.imu_note += " (its sigmas are the prior std of " + priors + ")";
  }
  load_odometer(a, in);
  // IMU stamps late against GNSS time: found from the data and taken out before the filter sees them, unless the
  // user set the shift or asked for KF-GINS's behaviour.
  if (est::imu_latency_wanted(in.config, in.options, a.imu_latency, imu_time_shift_s != 0.0 || a.kfgins_compatible)) {
    in.latency = est::decide_drive_imu_latency(in.imu, in.gnss, in.config, in.options, a.refine_latency_in_filter);
    in.imu_note += in.latency.note;
  }
  decide_gnss_velocity_use(a, in);
  if (a.strict) {
    const std::vector<std::string> w = input_warnings(in);
    if (!w.empty()) {
      std::string all;
      for (const auto& x : w) all += "\n  " + x;
      throw InputError("--strict", 0, "the inputs are not clean:" + all);
    }
  }
  return in;
}

std::vector<std::string> input_count_lines(const NavInputs& in) {
  std::vector<std::string> out;
  for (const InputFileCounts& c : in.file_counts) {
    char pct[32];
    std::snprintf(pct, sizeof pct, "%.2f %%", 100.0 * c.dropped_fraction());
    out.push_back(c.role + " " + c.path + ": " + std::to_string(c.kept) + " records kept, " +
                  std::to_string(c.dropped.total()) + " dropped (" + pct + ")" +
                  (c.dropped.total() ? ": " + c.dropped.describe() : std::string()));
  }
  return out;
}

std::vector<std::string> input_warnings(const NavInputs& in) {
  std::vector<std::string> out;
  for (const InputFileCounts& c : in.file_counts) {
    if (c.dropped_fraction() <= kMaxDroppedFraction) continue;
    char msg[160];
    std::snprintf(msg, sizeof msg, "%s file dropped %.1f %% of its records (more than %.0f %%): ", c.role.c_str(),
                  100.0 * c.dropped_fraction(), 100.0 * kMaxDroppedFraction);
    out.push_back(msg + c.path + ": " + c.dropped.describe());
  }
  long long_gaps = 0;
  const ImuTimeGap* longest = nullptr;
  for (const ImuTimeGap& g : in.imu_gaps) {
    if (g.length_s() <= kMaxImuGap_s) continue;
    ++long_gaps;
    if (!longest || g.length_s() > longest->length_s()) longest = &g;
  }
  if (longest) {
    char msg[200];
    std::snprintf(msg, sizeof msg, "IMU has %ld gaps longer than %g s; the longest %.3f s from %.3f to %.3f s (line %ld)",
                  long_gaps, kMaxImuGap_s, longest->length_s(), longest->t_before_s, longest->t_after_s, longest->line);
    out.push_back(msg);
  }
  // GNSS that does not cover the IMU's time (wrong week, another day's file, a time-base mix-up) would
  // give a pure-inertial run that looks like a navigation result.
  if (!in.imu.empty() && !in.gnss.empty()) {
    const double imu_t0 = in.imu.front().t_s, imu_t1 = in.imu.back().t_s;
    long inside = 0;
    for (const GnssFix& f : in.gnss) inside += f.t_s >= imu_t0 && f.t_s <= imu_t1;
    const double covered = static_cast<double>(inside) / static_cast<double>(in.gnss.size());
    if (covered < 0.5) {
      char msg[240];
      std::snprintf(msg, sizeof msg,
                    "only %ld of %zu GNSS fixes (%.0f %%) fall within the IMU's time span %.3f - %.3f s (GNSS %.3f - %.3f s): "
                    "check the GPS week and time base of both files",
                    inside, in.gnss.size(), 100.0 * covered, imu_t0, imu_t1, in.gnss.front().t_s, in.gnss.back().t_s);
      out.push_back(msg);
    }
  }
  return out;
}

}  // namespace ldv::assess
