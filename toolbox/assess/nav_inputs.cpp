#include "toolbox/assess/nav_inputs.hpp"

#include <cstdio>
#include <cstdlib>
#include <optional>

#include "common/formats/kfgins_files.hpp"
#include "common/formats/tagged_imu_csv.hpp"
#include "common/io/input_error.hpp"
#include "estimator/run/run_navigation.hpp"
#include "services/gnss_link/protocols/rtklib_solution.hpp"
#include "toolbox/calib/imu_calibration.hpp"

namespace ldv::assess {
namespace {

Vec3 remap(const Vec3& v, const std::vector<int>& axes) {
  Vec3 out;
  for (int i = 0; i < 3; ++i) out(i) = (axes[i] > 0 ? 1.0 : -1.0) * v(std::abs(axes[i]) - 1);
  return out;
}

void check_axes(const std::vector<int>& axes) {
  int seen = 0;
  for (int a : axes)
    if (std::abs(a) >= 1 && std::abs(a) <= 3) seen |= 1 << std::abs(a);
  if (axes.size() != 3 || seen != 0b1110) throw InputError("--csv-axes", 0, "expected a permutation of 1 2 3 with signs, e.g. 1 -2 -3");
}

bool ends_with(const std::string& s, const char* suffix) {
  const std::string x(suffix);
  return s.size() >= x.size() && s.compare(s.size() - x.size(), x.size(), x) == 0;
}

// The calibration file: the command line's, else the configuration's ldv.calibration (resolved like imupath).
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
  if (!a.model.empty()) in.options.model = a.model;
  in.options.add.insert(in.options.add.end(), a.add.begin(), a.add.end());
  in.options.drop.insert(in.options.drop.end(), a.drop.begin(), a.drop.end());
  return in;
}

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
  if (!a.imu_csv.empty() || ends_with(imu_path, ".csv")) {
    check_axes(a.csv_axes);
    TaggedImuCsvReport rep;
    in.imu = read_tagged_imu_csv(imu_path, a.imu_tag.empty() ? imu_path + ".tag" : a.imu_tag, {}, &rep);
    in.file_counts.push_back({"IMU", imu_path, rep.samples, rep.dropped});
    in.imu_gaps = rep.long_gaps;
    calibrate();  // in the device axes, as `ldv calib static` saw them
    for (ImuIncrement& s : in.imu) {
      s.dtheta_b_rad = remap(s.dtheta_b_rad, a.csv_axes);
      s.dvel_b_mps = remap(s.dvel_b_mps, a.csv_axes);
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
  if (!a.rtklib_pos.empty() || ends_with(gnss_path, ".pos")) {
    const auto sols = gnss::read_rtklib_pos(gnss_path);
    DroppedRecords pos_dropped;
    for (const gnss::GnssSolution& s : sols) {
      GnssFix f = s.fix;
      f.pos.h_m += height_offset_m;
      if (f.quality != GnssQuality::kFixed && float_std_min_m > 0) f.pos_std_ned_m = f.pos_std_ned_m.cwiseMax(float_std_min_m);
      if (!in.gnss.empty() && f.t_s <= in.gnss.back().t_s) {  // repeated epochs
        pos_dropped.add(f.t_s == in.gnss.back().t_s ? DropReason::kRepeated : DropReason::kTimeBackwards, gnss_path, 0,
                        "epoch at " + std::to_string(f.t_s) + " s of week does not follow " +
                            std::to_string(in.gnss.back().t_s) + " s");
        continue;
      }
      in.gnss.push_back(f);
    }
    if (in.gnss.empty()) throw InputError(gnss_path, 0, "no solutions in the RTKLIB .pos file");
    in.file_counts.push_back({"GNSS", gnss_path, static_cast<long>(in.gnss.size()), pos_dropped});
    in.gps_week = sols.front().time.week;
  } else {
    GnssReadReport rep;
    in.gnss = read_kfgins_gnss(gnss_path, &rep);
    in.file_counts.push_back({"GNSS", gnss_path, rep.rows, rep.dropped});
  }
  in.description += " + " + gnss_path;
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
  return out;
}

}  // namespace ldv::assess
