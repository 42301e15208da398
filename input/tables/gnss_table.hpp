#pragma once
// GNSS positions as their owner published them: any delimited table described by the configuration's
// ldv.gnss_table, read into fixes. Issue 49's contract:
//   gnss_table:
//     path: GNSS.csv
//     time: {row_period_s: 0.01, offset_s: 300000}          # as ldv.imu_table's (input/tables/table_time.hpp)
//     position: {columns: [Lat_GNSS, Long_GNSS, Height_GNSS]}   # deg, deg, m (ellipsoidal); frame: ecef for X Y Z [m]
//     std_m: [0.02, 0.02, 0.04]                             # north, east, down: when the file has no std columns
//     std: {columns: [sN, sE, sD]}                          # or the file's own [m]
//     quality: {column: Q, fixed: [4], float: [5]}          # the solution type (other values: single); default fixed
//     height_offset_m: 0                                    # added to the heights (a geoid separation for MSL)
//     repeated: drop                                        # sample-and-hold rows: one fix per change (or keep)
// A std is required: stated or from columns. An unknown std is not a zero, and ldv cannot know it better than the
// user's first guess; the GNSS noise adaptation raises a std stated too small (it never lowers one).
#include <string>
#include <vector>

#include "common/config/config_section.hpp"
#include "common/formats/nav_types.hpp"
#include "common/io/dropped_records.hpp"
#include "input/tables/table_time.hpp"

namespace ldv::input {

struct GnssTable {
  std::string path;
  TableTime time;
  std::vector<std::string> position_columns;
  bool ecef = false;
  std::vector<std::string> std_columns;  // empty: stated_std_ned_m
  Vec3 stated_std_ned_m = Vec3::Zero();
  std::string quality_column;  // empty: every fix fixed
  std::vector<double> fixed_values, float_values;
  double height_offset_m = 0.0;
  bool drop_repeated = true;
  static GnssTable from(config::ConfigSection table, const std::string& config_path);
};

struct GnssTableReport {
  TableLayout layout;
  long rows = 0;
  long repeated_rows = 0;  // sample-and-hold rows dropped (each repeats the fix before it)
  DroppedRecords dropped;
};

std::vector<GnssFix> read_gnss_table(const GnssTable& table, GnssTableReport* report = nullptr);

}  // namespace ldv::input
