#include "input/tables/gnss_table.hpp"

#include <algorithm>
#include <cmath>

#include "common/formats/kfgins_config.hpp"
#include "common/geo/earth_model.hpp"
#include "common/io/input_error.hpp"
#include "input/tables/row_checks.hpp"

namespace ldv::input {
namespace {
bool trim_blank(std::string_view f) { return f.find_first_not_of(" \t\r") == std::string_view::npos; }
}  // namespace

GnssTable GnssTable::from(config::ConfigSection table, const std::string& config_path) {
  GnssTable t;
  t.path = resolve_data_path(table.text("path", ""), config_path);
  if (t.path.empty()) table.fail("path", "the table's file");
  t.time = TableTime::from(table.section("time"));
  config::ConfigSection position = table.section("position");
  t.position_columns = position.names("columns", {}, 3);
  if (t.position_columns.empty())
    position.fail("columns", "three column names (or 1-based indices): latitude, longitude [deg], height [m]");
  t.ecef = position.choice("frame", "geodetic", {"geodetic", "ecef"}) == "ecef";
  if (table.has("std")) {
    config::ConfigSection s = table.section("std");
    t.std_columns = s.names("columns", {}, 3);
    if (t.std_columns.empty()) s.fail("columns", "three column names: the north, east and down std [m]");
  }
  const std::vector<double> stated = table.numbers("std_m", {}, 3, config::Range::above(0.0).up_to(1e4));
  if (stated.empty() == t.std_columns.empty())
    table.fail("std_m",
               "the fixes' std: stated (std_m: [north, east, down] in m) when the file has none, or its "
               "columns (std: {columns: [...]}), one of them");
  if (!stated.empty()) t.stated_std_ned_m = Vec3(stated[0], stated[1], stated[2]);
  if (table.has("quality")) {
    config::ConfigSection q = table.section("quality");
    t.quality_column = q.text("column", "");
    if (t.quality_column.empty()) q.fail("column", "the column holding the solution type");
    t.fixed_values = q.number_list("fixed");
    t.float_values = q.number_list("float");
    if (t.fixed_values.empty()) q.fail("fixed", "the values of the quality column that mean an RTK fixed solution");
  }
  t.height_offset_m = table.number("height_offset_m", 0.0, config::Range::between(-1e4, 1e4));
  t.drop_repeated = table.choice("repeated", "drop", {"drop", "keep"}) == "drop";
  table.refuse_unknown();
  return t;
}

std::vector<GnssFix> read_gnss_table(const GnssTable& table, GnssTableReport* report) {
  GnssTableReport local;
  GnssTableReport& rep = report ? *report : local;
  rep.layout = sniff_table_layout(table.path);
  const TableLayout& layout = rep.layout;
  const RowClock clock(table.time, layout, table.path, "ldv.gnss_table.time.column");
  int pos[3], sd[3] = {-1, -1, -1};
  for (int i = 0; i < 3; ++i) {
    pos[i] = table_column(layout, table.position_columns[i], table.path, "ldv.gnss_table.position.columns");
    if (!table.std_columns.empty())
      sd[i] = table_column(layout, table.std_columns[i], table.path, "ldv.gnss_table.std.columns");
  }
  const int quality = table.quality_column.empty()
                          ? -1
                          : table_column(layout, table.quality_column, table.path, "ldv.gnss_table.quality.column");
  std::vector<GnssFix> out;
  Vec3 last_raw = Vec3::Constant(NAN);
  double t_prev = NAN;
  long index = -1;
  for_each_table_row(table.path, layout, [&](long line, const std::vector<std::string_view>& fields) {
    ++index;
    ++rep.rows;
    if (!row_has_layout_columns(fields, layout, table.path, line, rep.dropped)) return;
    double t = 0.0, q = 0.0;
    Vec3 raw, s = table.stated_std_ned_m;
    bool numbers = clock.time_of(index, fields, t) && (quality < 0 || parse_table_number(fields[quality], layout, q));
    for (int i = 0; i < 3 && numbers; ++i)
      numbers = parse_table_number(fields[pos[i]], layout, raw(i)) &&
                (sd[i] < 0 || parse_table_number(fields[sd[i]], layout, s(i)));
    if (!numbers) {
      const bool blank = trim_blank(fields[pos[0]]) && trim_blank(fields[pos[1]]) && trim_blank(fields[pos[2]]);
      rep.dropped.add(DropReason::kMalformed, table.path, line,
                      blank ? "no position in this row (blank fields: no fix yet?)"
                            : "a time, position, std or quality field is not a number");
      return;
    }
    // Sample-and-hold: a row repeating the fix before it is not a new measurement.
    if (table.drop_repeated && raw == last_raw) {
      ++rep.repeated_rows;
      return;
    }
    if (!time_follows(t, t_prev, table.path, line, rep.dropped)) return;
    GnssFix f;
    f.t_s = t;
    if (table.ecef) {
      f.pos = earth::geodetic_from_ecef(raw);
    } else {
      if (std::abs(raw(0)) > 90.0 || std::abs(raw(1)) > 360.0) {
        rep.dropped.add(DropReason::kOutOfRange, table.path, line,
                        "latitude / longitude out of range (expected degrees: |lat| <= 90, |lon| <= 360)");
        return;
      }
      f.pos = Geodetic{raw(0) * kDegToRad, wrap_pi(raw(1) * kDegToRad), raw(2)};
    }
    f.pos.h_m += table.height_offset_m;
    if (!std::isfinite(f.pos.lat_rad) || !std::isfinite(f.pos.lon_rad) || !std::isfinite(f.pos.h_m) ||
        std::abs(f.pos.lat_rad) > 0.5 * M_PI) {
      rep.dropped.add(DropReason::kOutOfRange, table.path, line, "a position beyond the Earth's coordinates");
      return;
    }
    if (!(s.minCoeff() > 0.0)) {
      rep.dropped.add(DropReason::kOutOfRange, table.path, line, "a std is not positive");
      return;
    }
    f.pos_std_ned_m = s;
    if (quality >= 0) {
      const auto is = [&](const std::vector<double>& v) { return std::find(v.begin(), v.end(), q) != v.end(); };
      f.quality = is(table.fixed_values)   ? GnssQuality::kFixed
                  : is(table.float_values) ? GnssQuality::kFloat
                                           : GnssQuality::kSingle;
    }
    out.push_back(f);
    last_raw = raw;
    t_prev = t;
  });
  if (out.empty())
    throw InputError(table.path, 0, "no GNSS fixes: no row with a time and a position (" + layout.describe() + ")");
  return out;
}

}  // namespace ldv::input
