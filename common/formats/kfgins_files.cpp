#include "common/formats/kfgins_files.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <memory>

#include "common/formats/gnss_solution_checks.hpp"
#include "common/formats/imu_sample_checks.hpp"
#include "common/formats/imu_time_gaps.hpp"
#include "common/io/text_table.hpp"
#include "common/logging.hpp"
#include "common/time/gps_time.hpp"

namespace ldv {
namespace {

std::string seconds(double t_s) {
  char b[48];
  std::snprintf(b, sizeof b, "%.6f s", t_s);
  return b;
}

// Too many dropped records mean the file or its declared layout is wrong: refuse it, naming the first of each.
void check_dropped(const std::string& path, const DroppedRecords& d, long data_lines, double max_fraction,
                   const std::string& hint) {
  if (d.total() == 0 || static_cast<double>(d.total()) <= max_fraction * static_cast<double>(data_lines)) return;
  throw InputError(path, 0,
                   std::to_string(d.total()) + " of " + std::to_string(data_lines) + " data lines dropped (more than " +
                       std::to_string(static_cast<int>(max_fraction * 100.0 + 0.5)) + " %" + hint + "): " +
                       d.describe());
}

struct ImuRow {
  ImuIncrement s;
  long line;
};

// Digits after the decimal point in the line's last field (-1 without a point): a last line that ends without a
// newline and with fewer of them than the line before was cut while written ("... -4." of "-4.123456789").
int decimals_of_last_field(std::string_view text) {
  size_t end = text.size();
  while (end > 0 && (text[end - 1] == ' ' || text[end - 1] == '\t' || text[end - 1] == '\r' || text[end - 1] == ','))
    --end;
  size_t begin = end;
  while (begin > 0 && text[begin - 1] != ' ' && text[begin - 1] != '\t' && text[begin - 1] != ',') --begin;
  const std::string_view field = text.substr(begin, end - begin);
  const size_t dot = field.find('.');
  if (dot == std::string_view::npos) return -1;
  size_t digits = 0;
  while (dot + 1 + digits < field.size() && field[dot + 1 + digits] >= '0' && field[dot + 1 + digits] <= '9') ++digits;
  return static_cast<int>(digits);
}

// The last line, unterminated, with a shorter last field than the line before, was cut while being written:
// dropped and counted (true). Otherwise its decimals become the reference for the next line.
bool drop_if_cut(const TextFileLines& lines, std::string_view text, int& previous_decimals, DroppedRecords& dropped,
                 const std::string& path, long line) {
  const int decimals = decimals_of_last_field(text);
  if (!lines.last_line_terminated() && previous_decimals > 0 && decimals < previous_decimals) {
    dropped.add(DropReason::kMalformed, path, line,
                "the last line ends without a newline and its last field is shorter than the line before's: "
                "cut while written");
    return true;
  }
  previous_decimals = decimals;
  return false;
}

// A time behind the record before: was the record before the corrupted one (one bad digit carried it ahead of
// both neighbours, farther ahead of this record than this one is after the record before it), or is this one
// stamped back? times: the kept records' times, t_s: this record's.
bool previous_jumped_ahead(double before_previous_s, double previous_s, double t_s) {
  return t_s > before_previous_s && previous_s - t_s > t_s - before_previous_s;
}

// Two samples closer than this are one sample twice (no IMU samples above 100 kHz; a .nav prints 1e-6 s).
constexpr double kMinImuInterval_s = 1e-5;

}  // namespace

std::vector<ImuIncrement> read_kfgins_imu(const std::string& path, ImuReadReport* report, const ImuReadOptions& opt) {
  // Hot path of `ldv nav` (200 Hz x hours): read in blocks, fields parsed straight into the samples, no per-row
  // allocation.
  if (opt.columns < 7 || opt.columns > 64)
    throw InputError(path, 0, opt.declared_by + " = " + std::to_string(opt.columns) + ": expected 7 to 64 columns");
  ImuReadReport rep;
  TextFileLines lines(path);
  std::vector<ImuRow> rows;
  rows.reserve(lines.estimated_lines());
  double v[64];
  FieldError err;
  std::string_view text;
  int previous_decimals = -1;
  while (lines.next(text)) {
    const long line = lines.line_number();
    const int n = scan_numeric_line(text, v, 64, &err);
    if (n == 0) continue;
    if (n < 0) {
      rep.dropped.add(err.non_finite ? DropReason::kNonFinite : DropReason::kMalformed, path, line, err.message());
      continue;
    }
    if (n != opt.columns) {
      rep.dropped.add(DropReason::kWrongColumns, path, line,
                      "expected " + std::to_string(opt.columns) + " columns (" + opt.declared_by + "), found " +
                          std::to_string(n));
      continue;
    }
    constexpr double kMaxTime_s = 1e10;  // 300 years
    if (std::abs(v[0]) > kMaxTime_s) {
      rep.dropped.add(DropReason::kOutOfRange, path, line, "column 1: time beyond 1e10 s");
      continue;
    }
    // What no IMU senses, judged as on the bus (imu_sample_checks.hpp) over the interval to the line before (the
    // first line, or one whose time repeats or does not follow, judged below: over the longest interval a sample
    // spans).
    const double interval_s =
        !rows.empty() && v[0] - rows.back().s.t_s >= kMinImuInterval_s ? v[0] - rows.back().s.t_s : kMaxImuInterval_s;
    if (const auto why = imu_rate_implausibility(Vec3(v[1], v[2], v[3]), Vec3(v[4], v[5], v[6]), interval_s)) {
      rep.dropped.add(DropReason::kOutOfRange, path, line, "an increment beyond any IMU: " + *why);
      continue;
    }
    if (drop_if_cut(lines, text, previous_decimals, rep.dropped, path, line)) continue;
    ImuRow r{{}, line};
    r.s.t_s = v[0];
    r.s.dtheta_b_rad = Vec3(v[1], v[2], v[3]);
    r.s.dvel_b_mps = Vec3(v[4], v[5], v[6]);
    if (!rows.empty()) {
      const double t_last = rows.back().s.t_s;
      if (std::abs(r.s.t_s - t_last) < kMinImuInterval_s) {
        rep.dropped.add(DropReason::kRepeated, path, line,
                        "time repeats (within 10 us of the line before): " + seconds(r.s.t_s));
        continue;
      }
      if (r.s.t_s < t_last) {
        // The record before jumped ahead of both neighbours: that one was corrupted, this one continues the run.
        // (One corrupted digit of a time stamp would otherwise drop every record up to the corrupted time.)
        const bool last_jumped =
            rows.size() >= 2 && previous_jumped_ahead(rows[rows.size() - 2].s.t_s, t_last, r.s.t_s);
        if (last_jumped) {
          rep.dropped.add(DropReason::kTimeJump, path, rows.back().line,
                          "time " + seconds(t_last) + " is ahead of both neighbours (" +
                              seconds(rows[rows.size() - 2].s.t_s) + ", " + seconds(r.s.t_s) + ")");
          rows.pop_back();
        } else {
          rep.dropped.add(DropReason::kTimeBackwards, path, line,
                          "time goes backwards: " + seconds(r.s.t_s) + " after " + seconds(t_last));
          continue;
        }
      }
    }
    rows.push_back(r);
  }
  check_dropped(path, rep.dropped, rows.size() + rep.dropped.total(), opt.max_dropped_fraction,
                ": is " + opt.declared_by + " = " + std::to_string(opt.columns) + " right?");
  if (rows.empty()) throw InputError(path, 0, "no IMU samples (expected rows: sow dtheta_xyz dvel_xyz)");

  std::vector<ImuIncrement> out;
  out.reserve(rows.size());
  for (size_t i = 0; i < rows.size(); ++i) {
    out.push_back(rows[i].s);
    if (i > 0) out.back().dt_s = rows[i].s.t_s - rows[i - 1].s.t_s;
  }
  if (out.size() > 1) out[0].dt_s = out[1].dt_s;
  // Gaps: intervals much longer than the median one (the data's own rate: a configuration's default imudatarate
  // of 200 Hz may not be the file's).
  std::vector<long> line_of;
  line_of.reserve(rows.size());
  for (const ImuRow& r : rows) line_of.push_back(r.line);
  const ImuGapSummary g = find_imu_gaps(out, line_of, opt.long_gap_factor);
  rep.nominal_dt_s = g.nominal_dt_s;
  rep.gaps = g.gaps;
  rep.long_gaps = g.long_gaps;
  rep.longest_gap_s = g.longest_gap_s;
  if (opt.rate_hz > 0 && out.size() > 1 && std::abs(g.nominal_dt_s * opt.rate_hz - 1.0) > 0.2)
    spdlog::warn("{}: median IMU interval {:g} s, but imudatarate says {:g} Hz", path, g.nominal_dt_s, opt.rate_hz);
  if (!g.long_gaps.empty())
    spdlog::warn("{}: {} gaps longer than {:g} median intervals; longest {:g} s", path, g.long_gaps.size(),
                 opt.long_gap_factor, g.longest_gap_s);
  rep.rows = static_cast<long>(out.size());
  if (report) *report = rep;
  return out;
}

void write_kfgins_imu(const std::string& path, const std::vector<ImuIncrement>& imu) {
  OutputFile f(path);
  std::vector<char> buf(static_cast<size_t>(1) << 16);
  size_t used = 0;
  for (const auto& s : imu) {
    if (used + 512 > buf.size()) {
      f.write(buf.data(), used);
      used = 0;
    }
    char* line = buf.data() + used;
    int n = format_fixed(line, s.t_s, 6);
    for (int i = 0; i < 3; ++i) {
      line[n++] = ' ';
      n += std::snprintf(line + n, 40, "%.15e", s.dtheta_b_rad[i]);
    }
    for (int i = 0; i < 3; ++i) {
      line[n++] = ' ';
      n += std::snprintf(line + n, 40, "%.15e", s.dvel_b_mps[i]);
    }
    line[n++] = '\n';
    used += static_cast<size_t>(n);
  }
  f.write(buf.data(), used);
  f.close();
}

std::vector<GnssFix> read_kfgins_gnss(const std::string& path, GnssReadReport* report) {
  std::vector<GnssFix> out;
  GnssReadReport rep;
  TextFileLines lines(path);
  std::vector<long> line_of;  // file line of each kept fix
  int previous_decimals = -1;
  double v[13];
  FieldError err;
  std::string_view text;
  while (lines.next(text)) {
    const long line = lines.line_number();
    const int n = scan_numeric_line(text, v, 13, &err);
    if (n == 0) continue;
    if (n < 0) {
      rep.dropped.add(err.non_finite ? DropReason::kNonFinite : DropReason::kMalformed, path, line, err.message());
      continue;
    }
    if (rep.columns == 0 && (n == 7 || n == 13)) rep.columns = n;
    if (n != rep.columns) {
      rep.dropped.add(DropReason::kWrongColumns, path, line,
                      "expected " + (rep.columns ? std::to_string(rep.columns) + " columns (as the first data line)"
                                                 : std::string("7 or 13 columns")) +
                          ", found " + std::to_string(n));
      continue;
    }
    GnssFix g;
    g.t_s = v[0];
    g.pos = {v[1] * kDegToRad, v[2] * kDegToRad, v[3]};
    if (n == 7) {
      g.pos_std_ned_m = Vec3(v[4], v[5], v[6]);
    } else {
      g.has_velocity = true;
      g.vel_n_mps = Vec3(v[4], v[5], v[6]);
      g.pos_std_ned_m = Vec3(v[7], v[8], v[9]);
      g.vel_std_n_mps = Vec3(v[10], v[11], v[12]);
    }
    if (std::abs(v[1]) > 90.0) {
      rep.dropped.add(DropReason::kOutOfRange, path, line, "column 2: latitude must be within +-90 deg");
      continue;
    }
    if ((g.pos_std_ned_m.array() <= 0).any() || (g.has_velocity && (g.vel_std_n_mps.array() <= 0).any())) {
      rep.dropped.add(DropReason::kOutOfRange, path, line, "every std must be positive");
      continue;
    }
    if (const auto why = gnss::implausibility(g)) {  // what the .pos reader and the bus refuse, refused here too
      rep.dropped.add(DropReason::kOutOfRange, path, line, *why);
      continue;
    }
    if (!out.empty() && g.t_s <= out.back().t_s) {
      const bool same = g.t_s == out.back().t_s;
      if (!same && out.size() >= 2 && previous_jumped_ahead(out[out.size() - 2].t_s, out.back().t_s, g.t_s)) {
        // One bad digit carried the record before ahead of both neighbours: that one is dropped, as for the IMU.
        rep.dropped.add(DropReason::kTimeJump, path, line_of.back(),
                        "time " + seconds(out.back().t_s) + " is ahead of both neighbours (" +
                            seconds(out[out.size() - 2].t_s) + ", " + seconds(g.t_s) + ")");
        out.pop_back();
        line_of.pop_back();
      } else {
        rep.dropped.add(same ? DropReason::kRepeated : DropReason::kTimeBackwards, path, line,
                        "time does not increase: " + seconds(g.t_s) + " after " + seconds(out.back().t_s));
        continue;
      }
    }
    if (drop_if_cut(lines, text, previous_decimals, rep.dropped, path, line)) continue;
    out.push_back(g);
    line_of.push_back(line);
  }
  check_dropped(path, rep.dropped, static_cast<long>(out.size()) + rep.dropped.total(), 0.10, "");
  if (out.empty()) throw InputError(path, 0, "no GNSS solutions (expected rows: sow lat lon h sN sE sD)");
  rep.rows = static_cast<long>(out.size());
  if (report) *report = rep;
  return out;
}

void write_kfgins_gnss(const std::string& path, const std::vector<GnssFix>& gnss, bool with_velocity) {
  OutputFile f(path);
  char line[1024];
  for (const auto& g : gnss) {
    int n = 0;
    if (with_velocity) {
      n = std::snprintf(line, sizeof line, "%.6f %.11f %.11f %.5f %.5f %.5f %.5f %.5f %.5f %.5f %.5f %.5f %.5f\n",
                        g.t_s, g.pos.lat_rad * kRadToDeg, g.pos.lon_rad * kRadToDeg, g.pos.h_m, g.vel_n_mps.x(),
                        g.vel_n_mps.y(), g.vel_n_mps.z(), g.pos_std_ned_m.x(), g.pos_std_ned_m.y(), g.pos_std_ned_m.z(),
                        g.vel_std_n_mps.x(), g.vel_std_n_mps.y(), g.vel_std_n_mps.z());
    } else {
      n = std::snprintf(line, sizeof line, "%.6f %.11f %.11f %.5f %.5f %.5f %.5f\n", g.t_s, g.pos.lat_rad * kRadToDeg,
                        g.pos.lon_rad * kRadToDeg, g.pos.h_m, g.pos_std_ned_m.x(), g.pos_std_ned_m.y(),
                        g.pos_std_ned_m.z());
    }
    // A value too long for the line (1e300 m) is cut by snprintf: refuse rather than write a cut row.
    if (n < 0 || n >= static_cast<int>(sizeof line))
      throw InputError(path, 0, "GNSS record at " + seconds(g.t_s) + ": a value too large to write");
    f.write(line, static_cast<size_t>(n));
  }
  f.close();
}

std::vector<NavRecord> read_nav(const std::string& path) {
  std::vector<NavRecord> out;
  read_numeric_table(path, 11, 64, [&](long line, const std::vector<double>& v) {
    if (!(v[0] >= 0.0 && v[0] <= 9999.0 && v[0] == std::floor(v[0])))
      throw InputError(path, line, "column 1: expected a GPS week (an integer 0..9999), found " + std::to_string(v[0]));
    // A position no vehicle has (latitude 1e308) would print as inf in every comparison made from it.
    if (!(std::abs(v[2]) <= 90.0)) throw InputError(path, line, "column 3: expected a latitude within +-90 deg");
    if (!(std::abs(v[3]) <= 360.0)) throw InputError(path, line, "column 4: expected a longitude within +-360 deg");
    NavRecord r;
    r.week = static_cast<int>(v[0]);
    r.sow_s = v[1];
    // In time order, as every comparison and interpolation of it needs (the error was "navigation series: time
    // goes backwards", naming no file or line).
    if (!out.empty() && (r.week - out.back().week) * kSecondsPerWeek + (r.sow_s - out.back().sow_s) < 0.0)
      throw InputError(path, line,
                       "time goes backwards: week " + std::to_string(r.week) + " " + seconds(r.sow_s) + " after week " +
                           std::to_string(out.back().week) + " " + seconds(out.back().sow_s) +
                           " (a .nav file is in time order)");
    r.pos = {v[2] * kDegToRad, v[3] * kDegToRad, v[4]};
    r.vel_n_mps = Vec3(v[5], v[6], v[7]);
    r.rpy_rad = Vec3(v[8], v[9], v[10]) * kDegToRad;
    out.push_back(r);
  });
  if (out.empty()) throw InputError(path, 0, "no navigation records (expected the 11-column .nav layout)");
  return out;
}

NavWriter::NavWriter(const std::string& path) : file_(path), buf_(static_cast<size_t>(1) << 20) {}

NavWriter::~NavWriter() {
  try {
    flush();
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
  }
}

void NavWriter::flush() {
  const size_t n = used_;
  used_ = 0;
  file_.write(buf_.data(), n);
}

void NavWriter::close() {
  flush();
  file_.close();
}

void NavWriter::write(const NavRecord& r) {
  static constexpr const char* kNames[] = {"sow", "lat", "lon", "h", "vN", "vE", "vD", "roll", "pitch", "yaw"};
  const double v[] = {r.sow_s,          r.pos.lat_rad * kRadToDeg, r.pos.lon_rad * kRadToDeg, r.pos.h_m,
                      r.vel_n_mps[0],   r.vel_n_mps[1],            r.vel_n_mps[2],            r.rpy_rad[0] * kRadToDeg,
                      r.rpy_rad[1] * kRadToDeg, r.rpy_rad[2] * kRadToDeg};
  static constexpr int kDecimals[] = {6, 11, 11, 5, 6, 6, 6, 8, 8, 8};
  constexpr int kFields = 10;
  for (int i = 0; i < kFields; ++i) {
    if (!std::isfinite(v[i])) {
      flush();  // the rows before it are kept
      throw InputError(file_.path(), rows_ + 1,
                       std::string("cannot write a non-finite ") + kNames[i] + " (" + std::to_string(v[i]) +
                           ") in the record at week " + std::to_string(r.week) + ", " + seconds(r.sow_s) +
                           ": the solution diverged; the " + std::to_string(rows_) + " rows before it are written");
    }
  }
  // Worst case of a row: the week and every field at format_fixed's longest, separators and the newline.
  constexpr size_t kMaxRow = 16 + kFields * (kFormatFixedMaxChars + 1) + 1;
  if (used_ + kMaxRow > buf_.size()) flush();
  char* line = buf_.data() + used_;
  int n = static_cast<int>(std::to_chars(line, line + 16, r.week).ptr - line);
  for (int i = 0; i < kFields; ++i) {
    line[n++] = ' ';
    n += format_fixed(line + n, v[i], kDecimals[i]);
  }
  line[n++] = '\n';
  used_ += static_cast<size_t>(n);
  ++rows_;
}

}  // namespace ldv
