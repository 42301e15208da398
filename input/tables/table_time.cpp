#include "input/tables/table_time.hpp"

#include <cmath>
#include <cstdio>
#include <string>

#include "common/time/utc_text.hpp"

namespace ldv::input {

TableTime TableTime::from(config::ConfigSection time) {
  TableTime t;
  t.offset_s = time.number("offset_s", 0.0, config::Range::between(-1e10, 1e10));
  t.column = time.text("column", "");
  t.date_column = time.text("date_column", "");
  t.row_period_s = time.number("row_period_s", 0.0, config::Range::at_least(0.0).up_to(3600.0));
  const bool counter = time.has("rate_hz");
  if (t.column.empty() == (t.row_period_s <= 0.0))
    time.fail("column", "give a time column (column: NAME) or the rows' period (row_period_s: P), one of them");
  if (counter) {
    const double rate_hz = time.number("rate_hz", 1.0, config::Range::above(0.0).up_to(1e9));
    t.seconds_per_unit = 1.0 / rate_hz;
    if (time.has("unit")) time.fail("unit", "a counter's unit is its rate_hz: give one of them");
  } else if (time.has("format")) {
    const std::string format = time.choice("format", "utc", {"utc", "gpst"});
    t.format = format == "utc" ? TableTime::Format::kUtcText : TableTime::Format::kGpstText;
    if (time.has("unit")) time.fail("unit", "a date-time column has no unit: give format or unit, one of them");
    if (t.column.empty()) time.fail("format", "a date-time format needs its column (column: NAME)");
  } else {
    const std::string unit = time.choice("unit", "s", {"s", "ms", "us", "ns"});
    t.seconds_per_unit = unit == "ms" ? 1e-3 : unit == "us" ? 1e-6 : unit == "ns" ? 1e-9 : 1.0;
  }
  if (t.column.empty() && counter) time.fail("rate_hz", "a counter's rate needs its column");
  if (!t.date_column.empty() && (t.format == Format::kNumber || t.column.empty()))
    time.fail("date_column",
              "a date column goes with the time-of-day column and its format (column: NAME, format: utc|gpst)");
  return t;
}

std::string TableTime::describe() const {
  char s[160];
  if (column.empty())
    std::snprintf(s, sizeof s, "row x %.6g s + %.10g s", row_period_s, offset_s);
  else if (format != Format::kNumber)
    std::snprintf(s, sizeof s, "column%s %s%s%s as %s date-times + %.10g s", date_column.empty() ? "" : "s",
                  date_column.c_str(), date_column.empty() ? "" : " ", column.c_str(),
                  format == Format::kUtcText ? "UTC" : "GPST", offset_s);
  else
    std::snprintf(s, sizeof s, "column %s x %.6g s + %.10g s", column.c_str(), seconds_per_unit, offset_s);
  return s;
}

RowClock::RowClock(const TableTime& time, const TableLayout& layout, const std::string& path, const std::string& key)
    : time_(time), layout_(&layout) {
  if (!time.column.empty()) column_ = table_column(layout, time.column, path, key);
  if (!time.date_column.empty()) date_column_ = table_column(layout, time.date_column, path, key);
}

bool RowClock::time_of(long row_index, const std::vector<std::string_view>& fields, double& t_s) const {
  if (column_ < 0) {
    t_s = time_.offset_s + static_cast<double>(row_index) * time_.row_period_s;
    return true;
  }
  if (column_ >= static_cast<int>(fields.size())) return false;
  if (time_.format != TableTime::Format::kNumber) {
    DateTimeText d;
    if (date_column_ >= static_cast<int>(fields.size())) return false;
    const bool parsed = date_column_ >= 0
                            ? parse_date_time(std::string(fields[date_column_]) + " " + std::string(fields[column_]), d)
                            : parse_date_time(fields[column_], d);
    if (!parsed) return false;
    // The text's clock (no leap seconds) to the instant in its scale, then UTC to GPS time at that UTC date; in whole
    // seconds (exact in a double since 1970), the fraction added to the seconds of week (1e9 s of total would round
    // a 100 Hz interval by 1e-8 s).
    const double whole_s = std::floor(d.calendar.second), fraction_s = d.calendar.second - whole_s;
    CalendarTime whole = d.calendar;
    whole.second = whole_s;
    GpsTime gps = GpsTime::from_total_seconds(gps_from_calendar(whole).total_seconds() - d.zone_east_s);
    if (time_.format == TableTime::Format::kUtcText) gps = gps_from_utc(calendar_from_gps(gps));
    t_s = time_.offset_s + weeks_.seconds(gps.week, gps.sow_s) + fraction_s;
    return true;
  }
  double v = 0.0;
  if (!parse_table_number(fields[column_], *layout_, v)) return false;
  t_s = time_.offset_s + v * time_.seconds_per_unit;
  return true;
}

}  // namespace ldv::input
