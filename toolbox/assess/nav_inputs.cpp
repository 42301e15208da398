#include "toolbox/assess/nav_inputs.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>

#include "common/config/config_section.hpp"
#include "common/formats/imu_calibration.hpp"
#include "common/formats/kfgins_files.hpp"
#include "common/formats/odometer_text.hpp"
#include "common/formats/rtklib_solution.hpp"
#include "common/formats/tagged_imu_csv.hpp"
#include "common/io/input_error.hpp"
#include "common/math/chi_square.hpp"
#include "common/math/device_axes.hpp"
#include "estimator/calibrate/drive_imu_latency.hpp"
#include "estimator/calibrate/gnss_velocity_check.hpp"
#include "estimator/filter/nav_filter.hpp"
#include "estimator/run/run_navigation.hpp"
#include "estimator/update/odometer.hpp"
#include "input/tables/gnss_table.hpp"
#include "input/tables/imu_table.hpp"

namespace ldv::assess {
namespace {

void check_axes(const std::vector<int>& axes) {
  if (!is_device_axes(axes))
    throw InputError("--csv-axes", 0, "expected a permutation of 1 2 3 with signs, e.g. 1 -2 -3");
}

bool ends_with(const std::string& s, const char* suffix) {
  const std::string x(suffix);
  return s.size() >= x.size() && s.compare(s.size() - x.size(), x.size(), x) == 0;
}

// The calibration file: the command line's, else the configuration's ldv.calibration (resolved like imupath).
// Seconds since the start of GPS week `ref_week`: continuous across a week rollover (sow restarts at 0,
// this goes on past 604800), so time order is the order of this number.
double continuous_seconds(const GpsTime& t, int ref_week) { return (t.week - ref_week) * kSecondsPerWeek + t.sow_s; }

// A .pos file's solutions in time order. Each record stands on its own time tag: one record stamped
// ahead (a glitch, or a real forward jump) is placed at its time instead of making every later one look
// repeated. Records at the same epoch as the one before are dropped (kept: the first in the file).
struct PosTimeOrder {
  std::vector<const gnss::GnssSolution*> solutions;
  long repeated = 0, out_of_order = 0;
};
PosTimeOrder in_time_order(const std::vector<gnss::GnssSolution>& sols, int& ref_week) {
  // The drive's first week (KF-GINS files count on from it past a rollover): the earliest week next to the
  // median one. One record of a far week (a corrupted date) must not move every other record's time (the
  // earliest week did: a record of 1980 put all the others 2300 weeks ahead of the IMU).
  std::vector<int> weeks;
  weeks.reserve(sols.size());
  for (const auto& s : sols) weeks.push_back(s.time.week);
  std::nth_element(weeks.begin(), weeks.begin() + weeks.size() / 2, weeks.end());
  const int median_week = weeks[weeks.size() / 2];
  ref_week = median_week;
  for (const auto& s : sols)
    if (s.time.week == median_week - 1) ref_week = median_week - 1;
  PosTimeOrder o;
  for (std::size_t i = 0; i < sols.size(); ++i) {
    if (i > 0 && sols[i].time.total_seconds() < sols[i - 1].time.total_seconds()) ++o.out_of_order;
    o.solutions.push_back(&sols[i]);
  }
  const auto t = [](const gnss::GnssSolution* s) { return s->time.total_seconds(); };
  std::stable_sort(o.solutions.begin(), o.solutions.end(), [&](auto* x, auto* y) { return t(x) < t(y); });
  constexpr double kSameEpoch_s = 1e-6;  // .pos prints milliseconds
  std::vector<const gnss::GnssSolution*> kept;
  for (const auto* s : o.solutions) {
    if (!kept.empty() && t(s) - t(kept.back()) < kSameEpoch_s) {
      ++o.repeated;
      continue;
    }
    kept.push_back(s);
  }
  o.solutions = std::move(kept);
  return o;
}

std::string calibration_path(const NavInputArgs& a, const KfGinsConfig& cfg) {
  if (!a.calibration.empty()) return a.calibration;
  if (!cfg.ldv.IsDefined() || cfg.ldv.IsNull() || !cfg.ldv["calibration"]) return "";
  const YAML::Node n = cfg.ldv["calibration"];
  if (!n.IsScalar() || n.Scalar().empty())
    throw InputError(cfg.config_path, n.Mark().line + 1, "key 'ldv.calibration': expected the path of a calibration file");
  return resolve_data_path(n.Scalar(), cfg.config_path);
}

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
  if (!a.imu.empty()) in.config.imu_path = a.imu;
  if (!a.imu_csv.empty()) in.config.imu_path = a.imu_csv;
  if (!a.gnss.empty()) in.config.gnss_path = a.gnss;
  if (!a.rtklib_pos.empty()) in.config.gnss_path = a.rtklib_pos;

  // A user's own tables (ldv.imu_table / ldv.gnss_table: input/tables/) unless the command line names a file.
  const auto table_section = [&](const char* key) {
    return config::ConfigSection(in.config.ldv[key], in.config.config_path, std::string("ldv.") + key + ".");
  };
  std::optional<input::ImuTable> imu_table;
  std::optional<input::GnssTable> gnss_table;
  if (a.imu.empty() && a.imu_csv.empty() && has_ldv_key(in.config, "imu_table")) {
    imu_table = input::ImuTable::from(table_section("imu_table"), in.config.config_path);
    in.config.imu_path = imu_table->path;
  }
  if (a.gnss.empty() && a.rtklib_pos.empty() && has_ldv_key(in.config, "gnss_table")) {
    gnss_table = input::GnssTable::from(table_section("gnss_table"), in.config.config_path);
    in.config.gnss_path = gnss_table->path;
  }

  const std::string& imu_path = in.config.imu_path;
  if (imu_path.empty()) throw InputError("ldv", 0, "give --kfgins-config FILE, or --imu FILE (or --imu-csv FILE)");
  // Loaded before the IMU file so a bad calibration is reported before a long read.
  const std::string cal_path = calibration_path(a, in.config);
  std::optional<calib::ImuCalibration> cal;
  if (!cal_path.empty()) cal = calib::load_calibration(cal_path);
  const auto calibrate = [&] {
    if (cal)
      for (ImuIncrement& s : in.imu) s = calib::apply_calibration(*cal, s);
  };
  if (imu_table) {
    input::ImuTableReport rep;
    in.imu = input::read_imu_table(*imu_table, &rep);
    in.file_counts.push_back({"IMU", imu_path, static_cast<long>(in.imu.size()), rep.dropped});
    in.imu_gaps = rep.long_gaps;
    calibrate();  // the table's rows are in front-right-down already
    in.imu_note = "ldv.imu_table: " + rep.layout.describe() + "; time " + imu_table->time.describe() + "; " +
                  std::to_string(rep.long_gaps.size()) + " gaps";
  } else if (!a.imu_csv.empty() || ends_with(imu_path, ".csv")) {
    check_axes(a.csv_axes);
    TaggedImuCsvReport rep;
    in.imu = read_tagged_imu_csv(imu_path, a.imu_tag.empty() ? imu_path + ".tag" : a.imu_tag, {}, &rep);
    in.file_counts.push_back({"IMU", imu_path, rep.samples, rep.dropped});
    in.imu_gaps = rep.long_gaps;
    // The tags' jitter from the rows themselves: the trapezoid's increments no longer show which rows repeated.
    // Measured here or not at all: the run would read the reads' scatter in the increments, not the samples'.
    if (in.options.imu_stamp_jitter_from_tags) {
      in.imu_stamp_jitter = est::measure_imu_stamp_jitter(rep.distinct_sample_tags_s, rep.samples, rep.repeated_rows);
      if (in.imu_stamp_jitter.found) in.options.imu_stamp_jitter_s = in.imu_stamp_jitter.sigma_s;
      in.options.imu_stamp_jitter_from_tags = false;
    }
    calibrate();  // in the device axes, as `ldv calib static` saw them
    for (ImuIncrement& s : in.imu) {
      s.dtheta_b_rad = device_to_frd(s.dtheta_b_rad, a.csv_axes);
      s.dvel_b_mps = device_to_frd(s.dvel_b_mps, a.csv_axes);
    }
    in.imu_note = std::to_string(rep.skipped_lines) + " malformed lines and " + std::to_string(rep.skipped_counter) +
                  " bad counters skipped, " + std::to_string(rep.gaps) + " gaps; counter rate from " + rep.rate_source +
                  "; tag positions count line ends " + rep.line_ends;
    if (rep.counter_wraps > 0)
      in.imu_note += "; " + std::to_string(rep.counter_wraps) + " counter wraps at " + std::to_string(rep.counter_bits) +
                     " bits unwrapped";
  } else {
    ImuReadReport rep;
    ImuReadOptions ro;
    if (!a.config.empty()) {  // the configuration declares the layout (KF-GINS imudatalen, imudatarate)
      ro.columns = in.config.imu_data_columns;
      ro.rate_hz = in.config.imu_rate_hz;
      ro.declared_by = "imudatalen in " + a.config;
    } else {
      ro.declared_by = "the KF-GINS layout; a config's imudatalen";
    }
    in.imu = read_kfgins_imu(imu_path, &rep, ro);
    in.file_counts.push_back({"IMU", imu_path, rep.rows, rep.dropped});
    in.imu_gaps = rep.long_gaps;
    calibrate();
    in.imu_note = std::to_string(rep.dropped.total()) + " records dropped, " + std::to_string(rep.gaps) + " gaps";
  }
  if (cal) {
    in.imu_note += "; calibration " + cal_path + " applied";
    const std::string priors = take_priors_from(*cal, in.config, in.options);
    if (!priors.empty()) in.imu_note += " (its sigmas are the prior std of " + priors + ")";
  }
  for (ImuIncrement& s : in.imu) s.t_s += imu_time_shift_s;
  in.description = imu_path;

  const std::string& gnss_path = in.config.gnss_path;
  if (gnss_path.empty()) throw InputError("ldv", 0, "give --kfgins-config FILE, or --gnss FILE (or --pos FILE)");
  if (gnss_table) {
    input::GnssTableReport rep;
    in.gnss = input::read_gnss_table(*gnss_table, &rep);
    in.file_counts.push_back({"GNSS", gnss_path, static_cast<long>(in.gnss.size()), rep.dropped});
    in.gnss_note = "ldv.gnss_table: " + rep.layout.describe() + "; " + std::to_string(rep.repeated_rows) +
                   " sample-and-hold rows dropped (each repeats the fix before it)";
  } else if (!a.rtklib_pos.empty() || ends_with(gnss_path, ".pos")) {
    gnss::RtklibReadReport rep;
    const auto sols = gnss::read_rtklib_pos(gnss_path, {}, &rep);
    if (sols.empty()) throw InputError(gnss_path, 0, "no solutions in the RTKLIB .pos file");
    const PosTimeOrder order = in_time_order(sols, in.gps_week);
    for (const gnss::GnssSolution* s : order.solutions) {
      GnssFix f = s->fix;
      f.t_s = continuous_seconds(s->time, in.gps_week);
      f.pos.h_m += height_offset_m;
      if (f.quality != GnssQuality::kFixed && float_std_min_m > 0) f.pos_std_ned_m = f.pos_std_ned_m.cwiseMax(float_std_min_m);
      in.gnss.push_back(f);
    }
    DroppedRecords pos_dropped;  // the reader's malformed lines by reason, then the ordering's repeats
    for (const auto& [why, count] : rep.malformed_by_reason) {
      const auto first = rep.first_line_by_reason.find(why);
      const long line = first != rep.first_line_by_reason.end() ? first->second : 0;
      for (long k = 0; k < count; ++k) pos_dropped.add(DropReason::kMalformed, gnss_path, line, why);
    }
    for (long k = 0; k < order.repeated; ++k) pos_dropped.add(DropReason::kRepeated, gnss_path, 0, "repeated epoch");
    in.file_counts.push_back({"GNSS", gnss_path, static_cast<long>(in.gnss.size()), pos_dropped});
    in.gnss_note = rep.summary() + "; " + std::to_string(order.repeated) + " repeated epochs dropped, " +
                   std::to_string(order.out_of_order) + " out of file order";
  } else {
    GnssReadReport rep;
    in.gnss = read_kfgins_gnss(gnss_path, &rep);
    in.file_counts.push_back({"GNSS", gnss_path, rep.rows, rep.dropped});
  }
  in.description += " + " + gnss_path;
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
