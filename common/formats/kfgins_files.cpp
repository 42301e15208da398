#include "common/formats/kfgins_files.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

#include "common/io/text_table.hpp"

namespace ldv {
namespace {
using FilePtr = std::unique_ptr<std::FILE, int (*)(std::FILE*)>;
FilePtr open_for_writing(const std::string& path) {
  FilePtr f(std::fopen(path.c_str(), "wb"), &std::fclose);
  if (!f) throw InputError(path, 0, "cannot open file for writing");
  return f;
}
}  // namespace

std::vector<ImuIncrement> read_kfgins_imu(const std::string& path, ImuReadReport* report) {
  // Hot path of `ldv nav` (200 Hz x hours): the whole file in one read, fields parsed straight into
  // the samples, no per-row allocation (the table reader's checks and messages).
  std::vector<ImuIncrement> out;
  ImuReadReport rep;
  TextFileLines lines(path);
  out.reserve(lines.estimated_lines());
  double v[7];
  std::string_view text;
  while (lines.next(text)) {
    const long line = lines.line_number();
    const int n = parse_numeric_line(text, v, 7, path, line);
    if (n == 0) continue;
    if (n < 7 || n > 64) throw_column_count(path, line, 7, 64, n);
    ImuIncrement s;
    s.t_s = v[0];
    s.dtheta_b_rad = Vec3(v[1], v[2], v[3]);
    s.dvel_b_mps = Vec3(v[4], v[5], v[6]);
    if (!out.empty()) {
      const double dt = s.t_s - out.back().t_s;
      if (dt < 0) {
        throw InputError(path, line, "time goes backwards: " + std::to_string(s.t_s) + " s after " +
                                         std::to_string(out.back().t_s) + " s");
      }
      if (dt == 0) {
        ++rep.skipped_duplicates;
        continue;
      }
      s.dt_s = dt;
    }
    out.push_back(s);
  }
  if (out.empty()) throw InputError(path, 0, "no IMU samples (expected rows: sow dtheta_xyz dvel_xyz)");
  if (out.size() > 1) out[0].dt_s = out[1].dt_s;
  // Gaps: intervals much longer than the median interval.
  if (out.size() > 2) {
    std::vector<double> dts;
    dts.reserve(out.size());
    for (size_t i = 1; i < out.size(); ++i) dts.push_back(out[i].dt_s);
    std::nth_element(dts.begin(), dts.begin() + dts.size() / 2, dts.end());
    const double median = dts[dts.size() / 2];
    for (size_t i = 1; i < out.size(); ++i)
      if (out[i].dt_s > 1.5 * median) ++rep.gaps;
  }
  rep.rows = static_cast<long>(out.size());
  if (report) *report = rep;
  return out;
}

void write_kfgins_imu(const std::string& path, const std::vector<ImuIncrement>& imu) {
  auto f = open_for_writing(path);
  char line[512];
  for (const auto& s : imu) {
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
    std::fwrite(line, 1, n, f.get());
  }
}

std::vector<GnssFix> read_kfgins_gnss(const std::string& path) {
  std::vector<GnssFix> out;
  read_numeric_table(path, 7, 13, [&](long line, const std::vector<double>& v) {
    if (v.size() != 7 && v.size() != 13) {
      throw InputError(path, line, "expected 7 or 13 columns, found " + std::to_string(v.size()));
    }
    GnssFix g;
    g.t_s = v[0];
    if (std::abs(v[1]) > 90.0) throw InputError(path, line, "column 2: latitude must be within +-90 deg");
    g.pos = {v[1] * kDegToRad, v[2] * kDegToRad, v[3]};
    if (v.size() == 7) {
      g.pos_std_ned_m = Vec3(v[4], v[5], v[6]);
    } else {
      g.has_velocity = true;
      g.vel_n_mps = Vec3(v[4], v[5], v[6]);
      g.pos_std_ned_m = Vec3(v[7], v[8], v[9]);
      g.vel_std_n_mps = Vec3(v[10], v[11], v[12]);
      if ((g.vel_std_n_mps.array() <= 0).any())
        throw InputError(path, line, "velocity std (columns 11-13) must be positive");
    }
    if ((g.pos_std_ned_m.array() <= 0).any())
      throw InputError(path, line, "position std must be positive");
    if (!out.empty() && g.t_s <= out.back().t_s)
      throw InputError(path, line, "time does not increase: " + std::to_string(g.t_s) + " s after " +
                                       std::to_string(out.back().t_s) + " s");
    out.push_back(g);
  });
  if (out.empty()) throw InputError(path, 0, "no GNSS solutions (expected rows: sow lat lon h sN sE sD)");
  return out;
}

void write_kfgins_gnss(const std::string& path, const std::vector<GnssFix>& gnss, bool with_velocity) {
  auto f = open_for_writing(path);
  for (const auto& g : gnss) {
    if (with_velocity) {
      std::fprintf(f.get(), "%.6f %.11f %.11f %.5f %.5f %.5f %.5f %.5f %.5f %.5f %.5f %.5f %.5f\n", g.t_s,
                   g.pos.lat_rad * kRadToDeg, g.pos.lon_rad * kRadToDeg, g.pos.h_m, g.vel_n_mps.x(), g.vel_n_mps.y(),
                   g.vel_n_mps.z(), g.pos_std_ned_m.x(), g.pos_std_ned_m.y(), g.pos_std_ned_m.z(),
                   g.vel_std_n_mps.x(), g.vel_std_n_mps.y(), g.vel_std_n_mps.z());
    } else {
      std::fprintf(f.get(), "%.6f %.11f %.11f %.5f %.5f %.5f %.5f\n", g.t_s, g.pos.lat_rad * kRadToDeg,
                   g.pos.lon_rad * kRadToDeg, g.pos.h_m, g.pos_std_ned_m.x(), g.pos_std_ned_m.y(),
                   g.pos_std_ned_m.z());
    }
  }
}

std::vector<NavRecord> read_nav(const std::string& path) {
  std::vector<NavRecord> out;
  read_numeric_table(path, 11, 64, [&](long line, const std::vector<double>& v) {
    NavRecord r;
    r.week = static_cast<int>(v[0]);
    r.sow_s = v[1];
    r.pos = {v[2] * kDegToRad, v[3] * kDegToRad, v[4]};
    r.vel_n_mps = Vec3(v[5], v[6], v[7]);
    r.rpy_rad = Vec3(v[8], v[9], v[10]) * kDegToRad;
    out.push_back(r);
  });
  if (out.empty()) throw InputError(path, 0, "no navigation records (expected the 11-column .nav layout)");
  return out;
}

NavWriter::NavWriter(const std::string& path)
    : file_(std::fopen(path.c_str(), "wb")), path_(path), buf_(static_cast<size_t>(1) << 20) {
  if (!file_) throw InputError(path, 0, "cannot open file for writing");
}

NavWriter::~NavWriter() {
  if (file_) {
    flush();
    std::fclose(file_);
  }
}

void NavWriter::flush() {
  if (used_ > 0) std::fwrite(buf_.data(), 1, used_, file_);
  used_ = 0;
}

void NavWriter::write(const NavRecord& r) {
  if (used_ + 512 > buf_.size()) flush();
  char* line = buf_.data() + used_;
  int n = static_cast<int>(std::to_chars(line, line + 16, r.week).ptr - line);
  auto put = [&](double v, int decimals) {
    line[n++] = ' ';
    n += format_fixed(line + n, v, decimals);
  };
  put(r.sow_s, 6);
  put(r.pos.lat_rad * kRadToDeg, 11);
  put(r.pos.lon_rad * kRadToDeg, 11);
  put(r.pos.h_m, 5);
  for (int i = 0; i < 3; ++i) put(r.vel_n_mps[i], 6);
  for (int i = 0; i < 3; ++i) put(r.rpy_rad[i] * kRadToDeg, 8);
  line[n++] = '\n';
  used_ += static_cast<size_t>(n);
}

}  // namespace ldv
