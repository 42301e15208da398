#include "toolbox/calib/imu_log.hpp"

#include <cmath>
#include <algorithm>
#include <charconv>

#include "common/formats/kfgins_files.hpp"
#include "common/io/input_error.hpp"
#include "common/io/text_table.hpp"

namespace ldv::calib {

double accel_si_per_unit(const std::string& unit) {
  if (unit == "m/s^2" || unit == "mps2") return 1.0;
  if (unit == "g") return 9.80665;
  throw InputError("--acc-units", 0, "unknown accelerometer unit '" + unit + "' (m/s^2 or g)");
}

double gyro_si_per_unit(const std::string& unit) {
  if (unit == "rad/s") return 1.0;
  if (unit == "deg/s") return kDegToRad;
  if (unit == "deg/h") return kDegToRad / 3600.0;
  throw InputError("--gyro-units", 0, "unknown gyro unit '" + unit + "' (rad/s, deg/s or deg/h)");
}

namespace {

// Sample interval from time stamps (median is robust to the odd late sample) or from the given rate.
double sample_interval(const std::vector<double>& t, std::optional<double> rate_hz, const std::string& src) {
  if (rate_hz) {
    if (!(*rate_hz > 0.0)) throw InputError(src, 0, "--rate must be positive");
    return 1.0 / *rate_hz;
  }
  if (t.size() < 2) throw InputError(src, 0, "no time column and no --rate: cannot tell the sample interval");
  std::vector<double> d;
  d.reserve(t.size() - 1);
  for (size_t i = 1; i < t.size(); ++i) d.push_back(t[i] - t[i - 1]);
  std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
  const double dt = d[d.size() / 2];
  if (!(dt > 0.0)) throw InputError(src, 0, "time stamps do not increase");
  return dt;
}

void check_length(const ImuLog& log) {
  if (log.size() < 10) throw InputError(log.source, 0, "too few samples (" + std::to_string(log.size()) + ")");
}

void fill_time_if_missing(ImuLog& log) {
  if (!log.t_s.empty()) return;
  log.t_s.resize(log.size());
  for (size_t i = 0; i < log.size(); ++i) log.t_s[i] = static_cast<double>(i) * log.dt_s;
}

}  // namespace

ImuLog read_xyz_pair(const std::string& accel_path, const std::string& gyro_path, const ImuLogOptions& opt) {
  ImuLog log;
  log.source = accel_path + (gyro_path.empty() ? "" : " + " + gyro_path);
  std::vector<double> t_gyro;
  double t_prev = -1e300;
  read_numeric_table(accel_path, 4, 4, [&](long line, const std::vector<double>& v) {
    if (v[0] <= t_prev) throw InputError(accel_path, line, "time does not increase");
    t_prev = v[0];
    log.t_s.push_back(v[0]);
    log.f_mps2.emplace_back(opt.accel.to_si(v[1]), opt.accel.to_si(v[2]), opt.accel.to_si(v[3]));
  });
  if (!gyro_path.empty()) {
    read_numeric_table(gyro_path, 4, 4, [&](long line, const std::vector<double>& v) {
      const size_t i = t_gyro.size();
      if (i >= log.t_s.size() || std::abs(v[0] - log.t_s[i]) > 1e-6)
        throw InputError(gyro_path, line, "time stamp does not match the accelerometer file's sample " +
                                              std::to_string(i + 1));
      t_gyro.push_back(v[0]);
      log.w_rad_s.emplace_back(opt.gyro.to_si(v[1]), opt.gyro.to_si(v[2]), opt.gyro.to_si(v[3]));
    });
    if (t_gyro.size() != log.t_s.size())
      throw InputError(gyro_path, 0, "holds " + std::to_string(t_gyro.size()) + " samples, the accelerometer file " +
                                         std::to_string(log.t_s.size()));
  }
  check_length(log);
  log.dt_s = sample_interval(log.t_s, opt.rate_hz, accel_path);
  return log;
}

ImuLog read_csv_log(const std::string& path, const ImuLogOptions& opt) {
  TextFileLines in(path);  // bounded line length; refuses devices and directories
  ImuLog log;
  log.source = path;
  std::optional<double> header_rate;
  std::vector<std::string> columns = opt.columns;
  std::vector<std::string_view> fields;
  std::string line;
  long line_no = 0;
  bool in_data = false;
  int col_t = -1, col_a[3] = {-1, -1, -1}, col_g[3] = {-1, -1, -1};
  auto map_columns = [&]() {
    for (size_t c = 0; c < columns.size(); ++c) {
      const std::string& n = columns[c];
      if (n == "t") col_t = static_cast<int>(c);
      for (int k = 0; k < 3; ++k) {
        if (n == std::string("a") + "xyz"[k]) col_a[k] = static_cast<int>(c);
        if (n == std::string("g") + "xyz"[k]) col_g[k] = static_cast<int>(c);
      }
    }
    if (col_a[0] < 0 || col_a[1] < 0 || col_a[2] < 0)
      throw InputError(path, line_no, "columns ax, ay, az not all named (use --columns, e.g. t,ax,ay,az,gx,gy,gz)");
  };
  auto is_number = [](std::string_view f) {
    double v;
    const char* b = f.data() + ((!f.empty() && f[0] == '+') ? 1 : 0);
    auto [p, ec] = std::from_chars(b, f.data() + f.size(), v);
    return ec == std::errc() && p == f.data() + f.size();
  };
  std::string_view text;
  while (in.next(text)) {
    line.assign(text);
    line_no = in.line_number();
    split_fields(line, fields);
    if (fields.empty() || fields[0][0] == '#' || fields[0][0] == '%') continue;
    if (!in_data && !is_number(fields[0])) {
      // Metadata keys may contain spaces ("Initialization time,36.5"): rejoin on the comma.
      const size_t comma = line.find(',');
      if (comma != std::string::npos && line.find(',', comma + 1) == std::string::npos) {
        const std::string key = line.substr(0, comma);
        std::string value = line.substr(comma + 1);
        while (!value.empty() && (value.back() == '\r' || value.back() == ' ')) value.pop_back();
        if (is_number(value)) {
          const double v = parse_double(value, path, line_no, 2);
          if (key == "Fs") header_rate = v;
          if (key == "Initialization time" && v > 0) log.init_static_s = v;
          continue;
        }
      }
      if (opt.columns.empty()) {
        columns.clear();
        for (auto f : fields) columns.emplace_back(f);
      }
      continue;
    }
    if (!in_data) {
      if (columns.empty()) throw InputError(path, line_no, "no column names: give --columns (e.g. t,ax,ay,az,gx,gy,gz)");
      map_columns();
      in_data = true;
    }
    if (fields.size() != columns.size())
      throw InputError(path, line_no, "expected " + std::to_string(columns.size()) + " columns, found " +
                                          std::to_string(fields.size()));
    auto value = [&](int c) { return parse_double(fields[c], path, line_no, c + 1); };
    if (col_t >= 0) {
      const double t = value(col_t);
      if (!log.t_s.empty() && t <= log.t_s.back()) throw InputError(path, line_no, "time does not increase");
      log.t_s.push_back(t);
    }
    log.f_mps2.emplace_back(opt.accel.to_si(value(col_a[0])), opt.accel.to_si(value(col_a[1])),
                            opt.accel.to_si(value(col_a[2])));
    if (col_g[0] >= 0 && col_g[1] >= 0 && col_g[2] >= 0)
      log.w_rad_s.emplace_back(opt.gyro.to_si(value(col_g[0])), opt.gyro.to_si(value(col_g[1])),
                               opt.gyro.to_si(value(col_g[2])));
  }
  if (!in_data) throw InputError(path, 0, "no numeric data rows");
  check_length(log);
  log.dt_s = sample_interval(log.t_s, opt.rate_hz ? opt.rate_hz : header_rate, path);
  fill_time_if_missing(log);
  return log;
}

ImuLog read_kfgins_log(const std::string& path) {
  const std::vector<ImuIncrement> inc = read_kfgins_imu(path);
  ImuLog log;
  log.source = path;
  for (const ImuIncrement& s : inc) {
    if (!(s.dt_s > 0.0)) throw InputError(path, 0, "zero sample interval");
    log.t_s.push_back(s.t_s);
    log.f_mps2.push_back(s.dvel_b_mps / s.dt_s);
    log.w_rad_s.push_back(s.dtheta_b_rad / s.dt_s);
  }
  check_length(log);
  log.dt_s = sample_interval(log.t_s, std::nullopt, path);
  return log;
}

}  // namespace ldv::calib
