#pragma once
// A drive's IMU and GNSS sources, as the configuration names them and the command line overrides them, read into
// records on GPS time (the one place every command that reads a drive goes through: toolbox/assess/nav_inputs
// turns them into the estimator's inputs):
//   IMU : ldv.imu_table (input/tables/imu_table.hpp), a tagged CSV (.csv with its RTKLIB .tag), or KF-GINS imu.txt
//   GNSS: ldv.gnss_table (input/tables/gnss_table.hpp), an RTKLIB .pos, or KF-GINS gnss.txt
// An IMU calibration (`ldv calib static`) is applied in the device axes, then the axes are turned to
// front-right-down, then the user's known time shift is added.
#include <optional>
#include <string>
#include <vector>

#include "common/formats/imu_calibration.hpp"
#include "common/formats/kfgins_config.hpp"
#include "common/formats/nav_types.hpp"
#include "common/io/dropped_records.hpp"

namespace ldv::input {

// The command line's say over the sources (empty / zero: the configuration's).
struct SourceArgs {
  std::string imu, imu_csv, imu_tag;      // KF-GINS imu.txt; tagged CSV and its tag file (default CSV.tag)
  std::string gnss, rtklib_pos;           // KF-GINS gnss.txt; RTKLIB .pos
  std::vector<int> csv_axes = {1, 2, 3};  // the tagged CSV's device axes to front-right-down
  std::string calibration;                // IMU calibration file (else ldv.calibration)
  double pos_height_offset_m = 0.0;       // added to .pos heights (the geoid separation for MSL heights)
  double float_std_min_m = 0.0;           // lower bound on the std of .pos solutions that are not RTK-fixed
  double imu_time_shift_s = 0.0;          // added to every IMU time stamp
  bool imu_layout_declared = false;       // the configuration's imudatalen / imudatarate hold for imu.txt
};

// What a reader kept and dropped of one input file (printed by `ldv nav`).
struct SourceCounts {
  std::string role;  // "IMU", "GNSS", "odometer"
  std::string path;
  long kept = 0;
  DroppedRecords dropped;
  double dropped_fraction() const {
    const long n = kept + dropped.total();
    return n > 0 ? static_cast<double>(dropped.total()) / static_cast<double>(n) : 0.0;
  }
};

// The first time tag of each distinct IMU sample, where the reader knows them (a host-tagged CSV whose rows can
// repeat a sample): the tags' jitter is measured from them (estimator/calibrate/imu_stamp_jitter.hpp).
struct ImuSampleTags {
  bool known = false;
  std::vector<double> distinct_sample_tags_s;
  long rows = 0, repeated_rows = 0;
};

struct DriveSources {
  std::vector<ImuIncrement> imu;
  std::vector<GnssFix> gnss;
  std::vector<ImuTimeGap> imu_gaps;  // IMU intervals > 10 median intervals (kept: the estimator decides)
  std::vector<SourceCounts> counts;  // IMU then GNSS
  std::string imu_note, gnss_note;   // what the readers skipped or assumed
  std::string description;           // "IMU + GNSS" paths, for the log
  int gps_week = -1;                 // a .pos file's earliest week, else -1
  std::optional<calib::ImuCalibration> calibration;  // applied to the IMU when given
  std::string calibration_path;
  ImuSampleTags tags;
};

// Reads both sources; cfg's imu_path / gnss_path become the files read. InputError naming the file, line and key.
DriveSources read_drive_sources(const SourceArgs& args, KfGinsConfig& cfg);

}  // namespace ldv::input
