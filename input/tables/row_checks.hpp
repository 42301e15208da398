#pragma once
// The checks every table reader makes on a row before reading it, each counting what it drops with its file:line.
#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include "common/io/delimited_table.hpp"
#include "common/io/dropped_records.hpp"

namespace ldv::input {

// The row has the layout's field count.
inline bool row_has_layout_columns(const std::vector<std::string_view>& fields, const TableLayout& layout,
                                   const std::string& path, long line, DroppedRecords& dropped) {
  if (static_cast<int>(fields.size()) == layout.columns) return true;
  dropped.add(DropReason::kWrongColumns, path, line,
              "expected " + std::to_string(layout.columns) + " columns, found " + std::to_string(fields.size()));
  return false;
}

// The row's time comes after the last kept row's (NaN: none kept yet).
inline bool time_follows(double t_s, double t_prev_s, const std::string& path, long line, DroppedRecords& dropped) {
  if (!std::isfinite(t_prev_s) || t_s > t_prev_s) return true;
  dropped.add(t_s == t_prev_s ? DropReason::kRepeated : DropReason::kTimeBackwards, path, line,
              "time " + std::to_string(t_s) + " s does not follow " + std::to_string(t_prev_s) + " s");
  return false;
}

}  // namespace ldv::input
