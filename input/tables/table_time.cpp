#include "input/tables/table_time.hpp"

#include <cstdio>

namespace ldv::input {

TableTime TableTime::from(config::ConfigSection time) {
  TableTime t;
  t.offset_s = time.number("offset_s", 0.0, config::Range::between(-1e10, 1e10));
  t.column = time.text("column", "");
  t.row_period_s = time.number("row_period_s", 0.0, config::Range::at_least(0.0).up_to(3600.0));
  const bool counter = time.has("rate_hz");
  if (t.column.empty() == (t.row_period_s <= 0.0))
    time.fail("column", "give a time column (column: NAME) or the rows' period (row_period_s: P), one of them");
  if (counter) {
    const double rate_hz = time.number("rate_hz", 1.0, config::Range::above(0.0).up_to(1e9));
    t.seconds_per_unit = 1.0 / rate_hz;
    if (time.has("unit")) time.fail("unit", "a counter's unit is its rate_hz: give one of them");
  } else {
    const std::string unit = time.choice("unit", "s", {"s", "ms", "us", "ns"});
    t.seconds_per_unit = unit == "ms" ? 1e-3 : unit == "us" ? 1e-6 : unit == "ns" ? 1e-9 : 1.0;
  }
  if (t.column.empty() && counter) time.fail("rate_hz", "a counter's rate needs its column");
  return t;
}

std::string TableTime::describe() const {
  char s[160];
  if (column.empty())
    std::snprintf(s, sizeof s, "row x %.6g s + %.10g s", row_period_s, offset_s);
  else
    std::snprintf(s, sizeof s, "column %s x %.6g s + %.10g s", column.c_str(), seconds_per_unit, offset_s);
  return s;
}

RowClock::RowClock(const TableTime& time, const TableLayout& layout, const std::string& path, const std::string& key)
    : time_(time), layout_(&layout) {
  if (!time.column.empty()) column_ = table_column(layout, time.column, path, key);
}

bool RowClock::time_of(long row_index, const std::vector<std::string_view>& fields, double& t_s) const {
  if (column_ < 0) {
    t_s = time_.offset_s + static_cast<double>(row_index) * time_.row_period_s;
    return true;
  }
  double v = 0.0;
  if (column_ >= static_cast<int>(fields.size()) || !parse_table_number(fields[column_], *layout_, v)) return false;
  t_s = time_.offset_s + v * time_.seconds_per_unit;
  return true;
}

}  // namespace ldv::input
