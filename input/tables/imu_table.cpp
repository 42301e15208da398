#include "input/tables/imu_table.hpp"

#include <algorithm>
#include <cmath>

#include "common/formats/kfgins_config.hpp"
#include "common/geo/earth_model.hpp"
#include "common/io/input_error.hpp"
#include "common/math/device_axes.hpp"
#include "input/tables/row_checks.hpp"

namespace ldv::input {
namespace {

std::vector<std::string> three_columns(config::ConfigSection& s) {
  std::vector<std::string> cols = s.names("columns", {}, 3);
  if (cols.empty()) s.fail("columns", "three column names (or 1-based indices): the device's x, y, z");
  return cols;
}

}  // namespace

ImuTable ImuTable::from(config::ConfigSection table, const std::string& config_path) {
  ImuTable t;
  t.path = resolve_data_path(table.text("path", ""), config_path);
  if (t.path.empty()) table.fail("path", "the table's file");
  t.time = TableTime::from(table.section("time"));
  config::ConfigSection gyro = table.section("gyro"), accel = table.section("accel");
  t.gyro_columns = three_columns(gyro);
  t.accel_columns = three_columns(accel);
  // No default: a rate in deg/s read as rad/s is a vehicle spinning at 57x its turn rate.
  const std::string gu = gyro.choice("unit", "", {"deg/s", "rad/s", "deg/h", "rad", "deg"});
  const std::string au = accel.choice("unit", "", {"g", "mg", "m/s^2", "m/s"});
  t.gyro_to_si = gu == "deg/s" || gu == "deg" ? kDegToRad : gu == "deg/h" ? kDegToRad / 3600.0 : 1.0;
  t.gyro_increments = gu == "rad" || gu == "deg";
  t.accel_to_si = au == "g" ? earth::kStandardGravity_mps2 : au == "mg" ? 1e-3 * earth::kStandardGravity_mps2 : 1.0;
  t.accel_increments = au == "m/s";
  if (table.has("axes")) {
    const std::vector<double> a = table.numbers("axes", {1, 2, 3}, 3, config::Range::between(-3, 3));
    t.axes = {static_cast<int>(a[0]), static_cast<int>(a[1]), static_cast<int>(a[2])};
    if (!is_device_axes(t.axes) || a[0] != t.axes[0] || a[1] != t.axes[1] || a[2] != t.axes[2])
      table.fail("axes",
                 "the device axes that are front, right, down: a signed permutation of 1 2 3 (front-left-up: "
                 "[1, -2, -3])");
  }
  t.interval_mean = table.choice("sample", "instant", {"instant", "interval_mean"}) == "interval_mean";
  table.refuse_unknown();
  return t;
}

std::vector<ImuIncrement> read_imu_table(const ImuTable& table, ImuTableReport* report) {
  ImuTableReport local;
  ImuTableReport& rep = report ? *report : local;
  rep.layout = sniff_table_layout(table.path);
  const TableLayout& layout = rep.layout;
  const RowClock clock(table.time, layout, table.path, "ldv.imu_table.time.column");
  int gyro[3], accel[3];
  for (int i = 0; i < 3; ++i) {
    gyro[i] = table_column(layout, table.gyro_columns[i], table.path, "ldv.imu_table.gyro.columns");
    accel[i] = table_column(layout, table.accel_columns[i], table.path, "ldv.imu_table.accel.columns");
  }
  std::vector<ImuIncrement> out;
  std::vector<long> lines;  // of each increment's row
  double t_prev = NAN;
  Vec3 w_prev = Vec3::Zero(), f_prev = Vec3::Zero();
  long index = -1;
  for_each_table_row(table.path, layout, [&](long line, const std::vector<std::string_view>& fields) {
    ++index;
    ++rep.rows;
    if (!row_has_layout_columns(fields, layout, table.path, line, rep.dropped)) return;
    double t = 0.0;
    Vec3 w, f;
    bool numbers = clock.time_of(index, fields, t);
    for (int i = 0; i < 3 && numbers; ++i)
      numbers = parse_table_number(fields[gyro[i]], layout, w(i)) && parse_table_number(fields[accel[i]], layout, f(i));
    if (!numbers) {
      rep.dropped.add(DropReason::kMalformed, table.path, line, "a time, gyro or accelerometer field is not a number");
      return;
    }
    w = device_to_frd(w * table.gyro_to_si, table.axes);
    f = device_to_frd(f * table.accel_to_si, table.axes);
    if (!time_follows(t, t_prev, table.path, line, rep.dropped)) return;
    if (std::isfinite(t_prev)) {
      ImuIncrement inc;
      inc.t_s = t;
      inc.dt_s = t - t_prev;
      const double half = table.interval_mean ? 0.0 : 0.5;  // the trapezoid's weight on the row before
      inc.dtheta_b_rad = table.gyro_increments ? w : ((1.0 - half) * w + half * w_prev) * inc.dt_s;
      inc.dvel_b_mps = table.accel_increments ? f : ((1.0 - half) * f + half * f_prev) * inc.dt_s;
      if (!std::isfinite(inc.dt_s) || !inc.dtheta_b_rad.allFinite() || !inc.dvel_b_mps.allFinite()) {
        rep.dropped.add(DropReason::kOutOfRange, table.path, line, "an increment beyond any number (time or rate)");
        return;
      }
      out.push_back(inc);
      lines.push_back(line);
    }
    t_prev = t, w_prev = w, f_prev = f;
  });
  if (out.empty())
    throw InputError(table.path, 0,
                     "no IMU increments: fewer than two rows with a time and six numbers (" + layout.describe() + ")");
  std::vector<double> dts(out.size());
  for (size_t k = 0; k < out.size(); ++k) dts[k] = out[k].dt_s;
  std::nth_element(dts.begin(), dts.begin() + dts.size() / 2, dts.end());
  rep.median_interval_s = dts[dts.size() / 2];
  for (size_t k = 0; k < out.size(); ++k)
    if (out[k].dt_s > 10.0 * rep.median_interval_s)
      rep.long_gaps.push_back({out[k].t_s - out[k].dt_s, out[k].t_s, lines[k]});
  return out;
}

}  // namespace ldv::input
