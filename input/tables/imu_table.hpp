#pragma once
// An IMU as its owner published it: any delimited table (common/io/delimited_table.hpp) described by the
// configuration's ldv.imu_table, read into increments in front-right-down. Issue 49's contract:
//   imu_table:
//     path: GNSS.csv
//     time: {row_period_s: 0.01, offset_s: 300000}     # or {column: NAME, unit: s|ms|us|ns, offset_s: X}
//     gyro: {columns: [Gyro_X, Gyro_Y, Gyro_Z], unit: deg/s}   # deg/s rad/s deg/h, or increments: rad deg
//     accel: {columns: [Acc_X, Acc_Y, Acc_Z], unit: g}         # g mg m/s^2, or increments: m/s
//     axes: [1, -2, -3]                                        # device axes to front-right-down
//     sample: instant                                          # or interval_mean (below)
// A row stamped t_k holds the rates at t_k (`sample: instant`, a sensor's reading: the increment over [t_k-1, t_k]
// is their trapezoid) or their mean over [t_k-1, t_k] (`interval_mean`, an integrating sensor's output: rate x
// interval). Increments (rad, deg, m/s) are taken as they are, each ending at its row's time. The first row starts
// the clock and gives no increment.
#include <string>
#include <vector>

#include "common/config/config_section.hpp"
#include "common/formats/nav_types.hpp"
#include "common/io/dropped_records.hpp"
#include "input/tables/table_time.hpp"

namespace ldv::input {

struct ImuTable {
  std::string path;  // resolved against the configuration file
  TableTime time;
  std::vector<std::string> gyro_columns, accel_columns;
  double gyro_to_si = 1.0, accel_to_si = 1.0;  // rad/s (or rad) and m/s^2 (or m/s) per unit
  bool gyro_increments = false, accel_increments = false;
  std::vector<int> axes{1, 2, 3};
  bool interval_mean = false;
  // From the configuration's ldv.imu_table section; ConfigError naming the file, line and key.
  static ImuTable from(config::ConfigSection table, const std::string& config_path);
};

struct ImuTableReport {
  TableLayout layout;
  long rows = 0;  // data rows seen
  DroppedRecords dropped;
  double median_interval_s = 0.0;
  std::vector<ImuTimeGap> long_gaps;  // intervals beyond 10 median ones (kept: the estimator decides)
};

std::vector<ImuIncrement> read_imu_table(const ImuTable& table, ImuTableReport* report = nullptr);

}  // namespace ldv::input
