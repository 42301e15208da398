#include "input/drive_sources.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "common/config/config_section.hpp"
#include "common/formats/kfgins_files.hpp"
#include "common/formats/rtklib_solution.hpp"
#include "common/formats/tagged_imu_csv.hpp"
#include "common/io/input_error.hpp"
#include "common/math/device_axes.hpp"
#include "common/time/gps_time.hpp"
#include "input/tables/gnss_table.hpp"
#include "input/tables/imu_table.hpp"

namespace ldv::input {
namespace {

void check_axes(const std::vector<int>& axes) {
  if (!is_device_axes(axes))
    throw InputError("--csv-axes", 0, "expected a permutation of 1 2 3 with signs, e.g. 1 -2 -3");
}

// Increments read in the device's axes (a calibration is in them) into front-right-down.
void turn_to_frd(std::vector<ImuIncrement>& imu, const std::vector<int>& axes) {
  for (ImuIncrement& s : imu) {
    s.dtheta_b_rad = device_to_frd(s.dtheta_b_rad, axes);
    s.dvel_b_mps = device_to_frd(s.dvel_b_mps, axes);
  }
}

bool ends_with(const std::string& s, const char* suffix) {
  const std::string x(suffix);
  return s.size() >= x.size() && s.compare(s.size() - x.size(), x.size(), x) == 0;
}

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

// The calibration file: the command line's, else the configuration's ldv.calibration (resolved like imupath).
std::string calibration_path(const SourceArgs& a, const KfGinsConfig& cfg) {
  if (!a.calibration.empty()) return a.calibration;
  if (!cfg.ldv.IsDefined() || cfg.ldv.IsNull() || !cfg.ldv["calibration"]) return "";
  const YAML::Node n = cfg.ldv["calibration"];
  if (!n.IsScalar() || n.Scalar().empty())
    throw InputError(cfg.config_path, n.Mark().line + 1,
                     "key 'ldv.calibration': expected the path of a calibration file");
  return resolve_data_path(n.Scalar(), cfg.config_path);
}

}  // namespace

DriveSources read_drive_sources(const SourceArgs& a, KfGinsConfig& cfg) {
  DriveSources out;
  if (!a.imu.empty()) cfg.imu_path = a.imu;
  if (!a.imu_csv.empty()) cfg.imu_path = a.imu_csv;
  if (!a.gnss.empty()) cfg.gnss_path = a.gnss;
  if (!a.rtklib_pos.empty()) cfg.gnss_path = a.rtklib_pos;

  // A user's own tables (ldv.imu_table / ldv.gnss_table: input/tables/) unless the command line names a file.
  const auto table_section = [&](const char* key) {
    return config::ConfigSection(cfg.ldv[key], cfg.config_path, std::string("ldv.") + key + ".");
  };
  std::optional<ImuTable> imu_table;
  std::optional<GnssTable> gnss_table;
  if (a.imu.empty() && a.imu_csv.empty() && has_ldv_key(cfg, "imu_table")) {
    imu_table = ImuTable::from(table_section("imu_table"), cfg.config_path);
    cfg.imu_path = imu_table->path;
  }
  if (a.gnss.empty() && a.rtklib_pos.empty() && has_ldv_key(cfg, "gnss_table")) {
    gnss_table = GnssTable::from(table_section("gnss_table"), cfg.config_path);
    cfg.gnss_path = gnss_table->path;
  }

  const std::string& imu_path = cfg.imu_path;
  if (imu_path.empty()) throw InputError("ldv", 0, "give --kfgins-config FILE, or --imu FILE (or --imu-csv FILE)");
  // Loaded before the IMU file so a bad calibration is reported before a long read.
  const std::string cal_path = calibration_path(a, cfg);
  std::optional<calib::ImuCalibration> cal;
  if (!cal_path.empty()) cal = calib::load_calibration(cal_path);
  const auto calibrate = [&] {
    if (cal)
      for (ImuIncrement& s : out.imu) s = calib::apply_calibration(*cal, s);
  };
  if (imu_table) {
    ImuTableReport rep;
    ImuTable device_axes = *imu_table;  // read in the device axes: a calibration is in them
    device_axes.axes = {1, 2, 3};
    out.imu = read_imu_table(device_axes, &rep);
    out.counts.push_back({"IMU", imu_path, static_cast<long>(out.imu.size()), rep.dropped});
    out.imu_gaps = rep.long_gaps;
    calibrate();  // in the device axes, as `ldv calib static` saw them
    turn_to_frd(out.imu, imu_table->axes);
    out.imu_note = "ldv.imu_table: " + rep.layout.describe() + "; time " + imu_table->time.describe() + "; " +
                   std::to_string(rep.long_gaps.size()) + " gaps";
  } else if (!a.imu_csv.empty() || ends_with(imu_path, ".csv")) {
    check_axes(a.csv_axes);
    TaggedImuCsvReport rep;
    out.imu = read_tagged_imu_csv(imu_path, a.imu_tag.empty() ? imu_path + ".tag" : a.imu_tag, {}, &rep);
    out.counts.push_back({"IMU", imu_path, rep.samples, rep.dropped});
    out.imu_gaps = rep.long_gaps;
    // The rows' own tags: the trapezoid's increments no longer show which rows repeated.
    out.tags = {true, std::move(rep.distinct_sample_tags_s), rep.samples, rep.repeated_rows};
    calibrate();  // in the device axes, as `ldv calib static` saw them
    turn_to_frd(out.imu, a.csv_axes);
    out.imu_note = std::to_string(rep.skipped_lines) + " malformed lines and " + std::to_string(rep.skipped_counter) +
                   " bad counters skipped, " + std::to_string(rep.gaps) + " gaps; counter rate from " +
                   rep.rate_source + "; tag positions count line ends " + rep.line_ends;
    if (rep.counter_wraps > 0)
      out.imu_note += "; " + std::to_string(rep.counter_wraps) + " counter wraps at " +
                      std::to_string(rep.counter_bits) + " bits unwrapped";
  } else {
    ImuReadReport rep;
    ImuReadOptions ro;
    if (a.imu_layout_declared) {  // the configuration declares the layout (KF-GINS imudatalen, imudatarate)
      ro.columns = cfg.imu_data_columns;
      ro.rate_hz = cfg.imu_rate_hz;
      ro.declared_by = "imudatalen in " + cfg.config_path;
    } else {
      ro.declared_by = "the KF-GINS layout; a config's imudatalen";
    }
    out.imu = read_kfgins_imu(imu_path, &rep, ro);
    out.counts.push_back({"IMU", imu_path, rep.rows, rep.dropped});
    out.imu_gaps = rep.long_gaps;
    calibrate();
    out.imu_note = std::to_string(rep.dropped.total()) + " records dropped, " + std::to_string(rep.gaps) + " gaps";
  }
  if (cal) out.imu_note += "; calibration " + cal_path + " applied";
  out.calibration = cal;
  out.calibration_path = cal_path;
  for (ImuIncrement& s : out.imu) s.t_s += a.imu_time_shift_s;
  out.description = imu_path;

  const std::string& gnss_path = cfg.gnss_path;
  if (gnss_path.empty()) throw InputError("ldv", 0, "give --kfgins-config FILE, or --gnss FILE (or --pos FILE)");
  if (gnss_table) {
    GnssTableReport rep;
    out.gnss = read_gnss_table(*gnss_table, &rep);
    out.counts.push_back({"GNSS", gnss_path, static_cast<long>(out.gnss.size()), rep.dropped});
    out.gnss_note = "ldv.gnss_table: " + rep.layout.describe() + "; " + std::to_string(rep.repeated_rows) +
                    " sample-and-hold rows dropped (each repeats the fix before it)";
  } else if (!a.rtklib_pos.empty() || ends_with(gnss_path, ".pos")) {
    gnss::RtklibReadReport rep;
    const auto sols = gnss::read_rtklib_pos(gnss_path, {}, &rep);
    if (sols.empty()) throw InputError(gnss_path, 0, "no solutions in the RTKLIB .pos file");
    const PosTimeOrder order = in_time_order(sols, out.gps_week);
    for (const gnss::GnssSolution* s : order.solutions) {
      GnssFix f = s->fix;
      f.t_s = continuous_seconds(s->time, out.gps_week);
      f.pos.h_m += a.pos_height_offset_m;
      if (f.quality != GnssQuality::kFixed && a.float_std_min_m > 0)
        f.pos_std_ned_m = f.pos_std_ned_m.cwiseMax(a.float_std_min_m);
      out.gnss.push_back(f);
    }
    DroppedRecords pos_dropped;  // the reader's malformed lines by reason, then the ordering's repeats
    for (const auto& [why, count] : rep.malformed_by_reason) {
      const auto first = rep.first_line_by_reason.find(why);
      const long line = first != rep.first_line_by_reason.end() ? first->second : 0;
      for (long k = 0; k < count; ++k) pos_dropped.add(DropReason::kMalformed, gnss_path, line, why);
    }
    for (long k = 0; k < order.repeated; ++k) pos_dropped.add(DropReason::kRepeated, gnss_path, 0, "repeated epoch");
    out.counts.push_back({"GNSS", gnss_path, static_cast<long>(out.gnss.size()), pos_dropped});
    out.gnss_note = rep.summary() + "; " + std::to_string(order.repeated) + " repeated epochs dropped, " +
                    std::to_string(order.out_of_order) + " out of file order";
  } else {
    GnssReadReport rep;
    out.gnss = read_kfgins_gnss(gnss_path, &rep);
    out.counts.push_back({"GNSS", gnss_path, rep.rows, rep.dropped});
  }
  out.description += " + " + gnss_path;
  return out;
}

}  // namespace ldv::input
