#include "toolbox/allan/allan_input.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string_view>

#include "common/io/delimited_table.hpp"
#include "common/io/input_error.hpp"
#include "common/io/text_table.hpp"
#include "common/logging.hpp"
#include "toolbox/allan/sensor_units.hpp"

namespace ldv::allan {
namespace {

constexpr long kProgressRows = 2'000'000;

// Calls on_line(line_number, line) for every line of the file, reading 1 MiB chunks.
void for_each_line(const std::string& path, const std::function<void(long, std::string_view)>& on_line) {
  std::unique_ptr<FILE, int (*)(FILE*)> f(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!f) throw InputError(path, 0, "cannot open file for reading");
  std::vector<char> buffer(1 << 20);
  std::string carry;
  long line_no = 0;
  size_t got;
  while ((got = std::fread(buffer.data(), 1, buffer.size(), f.get())) > 0) {
    std::string_view chunk(buffer.data(), got);
    size_t start = 0;
    for (size_t i = 0; i < chunk.size(); ++i) {
      if (chunk[i] != '\n') continue;
      if (!carry.empty()) {
        carry.append(chunk.substr(start, i - start));
        on_line(++line_no, carry);
        carry.clear();
      } else {
        on_line(++line_no, chunk.substr(start, i - start));
      }
      start = i + 1;
    }
    carry.append(chunk.substr(start));
  }
  if (!carry.empty()) on_line(++line_no, carry);
}

bool is_comment(const std::vector<std::string_view>& fields) {
  return fields.empty() || fields[0][0] == '#' || fields[0][0] == '%';
}

bool looks_numeric(std::string_view s) {
  double v;
  const char* b = s.data();
  if (!s.empty() && *b == '+') ++b;
  auto [p, ec] = std::from_chars(b, s.data() + s.size(), v);
  return ec == std::errc() && p == s.data() + s.size();
}

// The sampling interval of a record from its time stamps, and what the stamps say against analysing it as one
// uniformly sampled series (issue 46: the median of jittered stamps took a 100 Hz record for 167 Hz, and holes
// went unsaid). The interval is the mean of the regular intervals (a jitter averages out; the median does not);
// a hole is an interval beyond 1.5 of it. Holes that hide more than 1 % of the record are refused (an Allan
// variance of a record with holes is not the sensor's); fewer are said and bridged as one sample each.
// `given_tau0_s` (--rate / --tau0), when > 0, is the interval; the stamps are then checked against it.
double sample_interval(const std::vector<double>& dts, const std::vector<long>& lines, const std::string& path,
                       double given_tau0_s) {
  if (dts.empty()) {
    if (given_tau0_s > 0) return given_tau0_s;
    throw InputError(path, 0, "cannot infer the sample interval from fewer than 2 time stamps: give --rate or --tau0");
  }
  double span = 0.0;
  for (const double dt : dts) span += dt;
  double interval = given_tau0_s > 0 ? given_tau0_s : span / static_cast<double>(dts.size());
  if (!(interval > 0.0)) throw InputError(path, 0, "time stamps do not increase: give --rate or --tau0");
  if (given_tau0_s <= 0) {  // the mean without the holes
    double sum = 0.0;
    long n = 0;
    for (const double dt : dts)
      if (dt <= 1.5 * interval) sum += dt, ++n;
    if (n > 0) interval = sum / static_cast<double>(n);
  }
  long holes = 0, first = -1;
  double missing_s = 0.0;
  for (size_t i = 0; i < dts.size(); ++i)
    if (dts[i] > 1.5 * interval) {
      ++holes;
      missing_s += dts[i] - interval;
      if (first < 0) first = static_cast<long>(i);
    }
  if (holes > 0) {
    char b[400];
    std::snprintf(b, sizeof b,
                  "%ld holes in the time stamps hiding %.6g s of %.6g s (the first: %.6g s before this line; the "
                  "interval is %.6g s)",
                  holes, missing_s, span, dts[first], interval);
    if (missing_s > 0.01 * span)
      throw InputError(path, lines[first],
                       std::string(b) +
                           ": an Allan variance needs one uniformly sampled record; analyse the pieces "
                           "between the holes apart");
    spdlog::warn("{}:{}: {}; analysed as one record, each hole bridged as one sample", path, lines[first], b);
  }
  // Jitter: the median and the mean interval apart by more than 10 % (say which is taken).
  std::vector<double> sorted(dts.begin(), dts.begin() + std::min<size_t>(dts.size(), 100000));
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  const double median = sorted[sorted.size() / 2];
  if (std::abs(median - interval) > 0.1 * interval)
    spdlog::warn("{}: irregular time stamps (median interval {:.6g} s, mean {:.6g} s): the {} is taken ({:.6g} Hz)",
                 path, median, interval, given_tau0_s > 0 ? "given interval" : "mean", 1.0 / interval);
  return interval;
}

double explicit_tau0(const InputOptions& opt) {
  if (opt.rate_hz < 0 || opt.tau0_s < 0) throw std::invalid_argument("--rate and --tau0 must be positive");
  if (opt.rate_hz > 0) return 1.0 / opt.rate_hz;
  return opt.tau0_s;  // 0 when not given
}

// A channel every analysis can use: enough samples and not constant.
void check_channel(const std::vector<double>& v, const std::string& path, const std::string& name) {
  if (v.empty()) throw InputError(path, 0, "no data rows");
  if (v.size() < 8) {
    throw InputError(path, 0, "channel " + name + ": " + std::to_string(v.size()) +
                                  " samples; at least 8 are needed for any deviation");
  }
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  if (*lo == *hi) throw InputError(path, 0, "channel " + name + " is constant (" + std::to_string(*lo) + "): nothing to analyse");
}

std::vector<PhaseSeries> read_kfgins(const std::string& path, const InputOptions& opt, const ProgressFn& progress) {
  if (!opt.units.empty() || !opt.columns.empty() || !opt.counts_per_unit.empty()) {
    throw std::invalid_argument("KF-GINS increments are rad and m/s by definition: --columns, --units and "
                                "--counts-per-unit do not apply (use --format csv for other layouts)");
  }
  static const char* names[6] = {"gyro_x", "gyro_y", "gyro_z", "accel_x", "accel_y", "accel_z"};
  std::vector<std::vector<double>> inc(6);
  std::vector<double> dts;
  std::vector<long> dt_lines;
  double t_prev = 0.0;
  long rows = 0;
  read_numeric_table(path, 7, 1000, [&](long line, const std::vector<double>& v) {
    if (rows > 0) {
      const double dt = v[0] - t_prev;
      if (!(dt > 0.0)) throw InputError(path, line, "column 1: time does not increase (" + std::to_string(v[0]) + " after " + std::to_string(t_prev) + ")");
      dts.push_back(dt);
      dt_lines.push_back(line);
    }
    t_prev = v[0];
    for (int c = 0; c < 6; ++c) inc[c].push_back(v[1 + c]);
    if (++rows % kProgressRows == 0 && progress) progress("read " + std::to_string(rows) + " rows");
  });
  const double tau0 = sample_interval(dts, dt_lines, path, explicit_tau0(opt));
  std::vector<PhaseSeries> out;
  for (int c = 0; c < 6; ++c) {
    check_channel(inc[c], path, names[c]);
    // Increment / nominal interval: the integral of the rate is then exactly the summed increments.
    for (double& v : inc[c]) v /= tau0;
    out.push_back(phase_from_rates(std::move(inc[c]), tau0, names[c], c < 3 ? "rad/s" : "m/s^2"));
  }
  return out;
}

// Per-column option lists: one value for all, or one per column.
template <typename T>
T per_column(const std::vector<T>& v, size_t i, T fallback, const char* what, size_t n) {
  if (v.empty()) return fallback;
  if (v.size() == 1) return v[0];
  if (v.size() != n) {
    throw std::invalid_argument(std::string(what) + ": give one value or one per column (" + std::to_string(n) +
                                "), got " + std::to_string(v.size()));
  }
  return v[i];
}

std::vector<PhaseSeries> read_csv(const std::string& path, const InputOptions& opt, const ProgressFn& progress) {
  // The layout from the file (a logger's preamble before the header, another separator: common/io/delimited_table).
  const TableLayout layout = sniff_table_layout(path);
  const auto find_column = [&](const std::string& key, const char* option) {
    return table_column(layout, key, path, option);
  };
  const auto column_name = [&](int c) {
    return layout.header.empty() ? "column " + std::to_string(c + 1) : layout.header[c];
  };
  const int time_col = opt.time_column.empty() ? -1 : find_column(opt.time_column, "--time-column");
  std::vector<int> cols;  // 0-based
  if (opt.columns.empty()) {
    for (int i = 0; i < layout.columns; ++i)
      if (i != time_col) cols.push_back(i);
  } else {
    for (const auto& c : opt.columns) cols.push_back(find_column(c, "--columns"));
  }
  std::vector<InputUnit> units;
  std::vector<double> scale;
  for (size_t i = 0; i < cols.size(); ++i) {
    units.push_back(parse_input_unit(per_column<std::string>(opt.units, i, "1", "--units", cols.size())));
    const double cpu = per_column<double>(opt.counts_per_unit, i, 1.0, "--counts-per-unit", cols.size());
    if (!(cpu != 0.0)) throw std::invalid_argument("--counts-per-unit must not be zero");
    scale.push_back(units.back().to_si / cpu);
  }
  std::vector<std::vector<double>> data(cols.size());
  std::vector<double> dts;
  std::vector<long> dt_lines;
  double t_prev = 0.0;
  long rows = 0;
  const auto number = [&](std::string_view field, long line, int col) {
    double v = 0.0;
    if (!parse_table_number(field, layout, v))
      throw InputError(path, line,
                       "column " + std::to_string(col + 1) + " (" + column_name(col) +
                           "): expected a finite number, found '" + std::string(field.substr(0, 40)) + "'");
    return v;
  };
  for_each_table_row(path, layout, [&](long line, const std::vector<std::string_view>& fields) {
    if (static_cast<int>(fields.size()) != layout.columns) {
      throw InputError(path, line,
                       "expected " + std::to_string(layout.columns) + " columns as in the rows before, found " +
                           std::to_string(fields.size()));
    }
    if (time_col >= 0) {
      const double t = number(fields[time_col], line, time_col);
      if (rows > 0) {
        if (!(t > t_prev))
          throw InputError(
              path, line,
              "time column: time does not increase (" + std::to_string(t) + " after " + std::to_string(t_prev) + ")");
        dts.push_back(t - t_prev);
        dt_lines.push_back(line);
      }
      t_prev = t;
    }
    for (size_t i = 0; i < cols.size(); ++i) data[i].push_back(number(fields[cols[i]], line, cols[i]) * scale[i]);
    if (++rows % kProgressRows == 0 && progress) progress("read " + std::to_string(rows) + " rows");
  });
  double tau0 = explicit_tau0(opt);
  if (tau0 == 0.0 && time_col < 0)
    throw InputError(path, 0, "the sample interval is unknown: give --rate, --tau0 or --time-column");
  if (time_col >= 0) tau0 = sample_interval(dts, dt_lines, path, tau0);
  std::vector<PhaseSeries> out;
  for (size_t i = 0; i < cols.size(); ++i) {
    check_channel(data[i], path, column_name(cols[i]));
    out.push_back(phase_from_rates(std::move(data[i]), tau0, column_name(cols[i]), units[i].si_name));
  }
  return out;
}

// Stable32 data files: up to two header lines, then one value per line (or "time value").
std::vector<PhaseSeries> read_stable32_style(const std::string& path, const InputOptions& opt) {
  std::vector<double> v;
  int header_lines = 0;
  std::vector<std::string_view> fields;
  for_each_line(path, [&](long line, std::string_view text) {
    split_fields(text, fields);
    if (is_comment(fields)) return;
    if (v.empty() && !looks_numeric(fields.back())) {
      if (++header_lines > 2) throw InputError(path, line, "expected a number (at most two header lines), found '" + std::string(text.substr(0, 60)) + "'");
      return;
    }
    if (fields.size() > 2) throw InputError(path, line, "expected one value or 'time value', found " + std::to_string(fields.size()) + " columns");
    const int c = static_cast<int>(fields.size());
    v.push_back(parse_double(fields.back(), path, line, c));
  });
  const bool phase = opt.format == InputFormat::kPhase;
  const InputUnit unit = parse_input_unit(per_column<std::string>(opt.units, 0, "1", "--units", 1));
  const double cpu = per_column<double>(opt.counts_per_unit, 0, 1.0, "--counts-per-unit", 1);
  double tau0 = explicit_tau0(opt);
  if (tau0 == 0.0) tau0 = 1.0;  // Stable32's default
  check_channel(v, path, phase ? "phase" : "frequency");
  std::vector<PhaseSeries> out;
  if (phase) {
    for (double& x : v) x *= unit.to_si / cpu;
    out.push_back(phase_from_phase(std::move(v), tau0, "phase", unit.si_name));
  } else {
    if (opt.nominal != 0.0) {
      for (double& y : v) y = (y - opt.nominal) / opt.nominal;
    } else {
      for (double& y : v) y *= unit.to_si / cpu;
    }
    out.push_back(phase_from_rates(std::move(v), tau0, "frequency", unit.si_name));
  }
  return out;
}

}  // namespace

InputFormat parse_input_format(const std::string& name) {
  if (name == "kfgins") return InputFormat::kKfGins;
  if (name == "csv") return InputFormat::kCsv;
  if (name == "phase") return InputFormat::kPhase;
  if (name == "frequency") return InputFormat::kFrequency;
  throw std::invalid_argument("unknown format '" + name + "' (expected kfgins, csv, phase or frequency)");
}

std::vector<PhaseSeries> read_allan_input(const std::string& path, const InputOptions& opt, const ProgressFn& progress) {
  try {
    switch (opt.format) {
      case InputFormat::kKfGins: return read_kfgins(path, opt, progress);
      case InputFormat::kCsv: return read_csv(path, opt, progress);
      case InputFormat::kPhase:
      case InputFormat::kFrequency: return read_stable32_style(path, opt);
    }
  } catch (const std::invalid_argument& e) {
    throw InputError(path, 0, e.what());  // option errors name the file they were applied to
  }
  return {};
}

}  // namespace ldv::allan
