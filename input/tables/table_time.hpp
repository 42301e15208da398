#pragma once
// When a table's row was taken, as its configuration describes it (`time:` of ldv.imu_table / ldv.gnss_table):
//   {column: NAME, unit: s|ms|us|ns, offset_s: X}   a time column (GPS seconds of week once offset_s is added)
//   {column: NAME, format: utc|gpst, offset_s: X}    a date-time column ("2024-08-27T17:30:01.123Z", "2024/08/27
//                                                   17:30:01.123"; a stated zone is applied, UTC goes to GPS time
//                                                   with the leap seconds), in seconds of the first row's GPS week
//   {date_column: D, column: T, format: utc|gpst}    the same split in two fields (a whitespace table's date and time)
//   {column: NAME, rate_hz: R, offset_s: X}         a sample counter ticking at R
//   {row_period_s: P, offset_s: X}                  no usable column: row k (from 0) at X + k P (a logger whose time
//                                                   column steps by 0.1 s while its rows come at 100 Hz)
#include <string>
#include <string_view>
#include <vector>

#include "common/config/config_section.hpp"
#include "common/io/delimited_table.hpp"
#include "common/time/gps_time.hpp"

namespace ldv::input {

struct TableTime {
  std::string column;  // empty: from the row index
  std::string
      date_column;  // a date-time split in two fields (a whitespace table's "2024/08/27 17:30:01.123"): the date
  enum class Format { kNumber, kUtcText, kGpstText } format = Format::kNumber;
  double seconds_per_unit = 1.0;
  double row_period_s = 0.0;  // > 0 with no column
  double offset_s = 0.0;
  // From the `time` section (ConfigError naming the file, line and key on a wrong or missing key).
  static TableTime from(config::ConfigSection time);
  // "column t_ms [ms] + 300000 s" / "row x 0.01 s + 300000 s"
  std::string describe() const;
};

// The time of each row in turn: t(fields) for the row_index-th data row (0-based); false when the column's field is
// not a number.
class RowClock {
 public:
  RowClock(const TableTime& time, const TableLayout& layout, const std::string& path, const std::string& key);
  bool time_of(long row_index, const std::vector<std::string_view>& fields, double& t_s) const;
  int column() const { return column_; }

 private:
  TableTime time_;
  const TableLayout* layout_;
  int column_ = -1, date_column_ = -1;
  mutable ContinuousGpsTime weeks_;  // date-time columns: seconds of the first row's week
};

}  // namespace ldv::input
