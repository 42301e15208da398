#pragma once
// KF-GINS / i2Nav text formats (DESIGN.md section 7):
//  imu.txt  : sow, dtheta x y z [rad], dvel x y z [m/s]  (front-right-down increments; extra columns ignored)
//  gnss.txt : sow, lat lon [deg], h [m], std N E D [m]                      (7 columns)
//             sow, lat lon [deg], h [m], vN vE vD [m/s], std N E D [m], std vN vE vD [m/s]   (13 columns)
//  .nav     : week, sow, lat lon [deg], h [m], vN vE vD [m/s], roll pitch yaw [deg]
#include <cstdio>
#include <string>
#include <vector>

#include "common/formats/nav_types.hpp"
#include "common/io/dropped_records.hpp"
#include "common/io/output_file.hpp"

namespace ldv {

struct ImuReadReport {
  long rows = 0;              // records kept
  DroppedRecords dropped;     // records dropped, by reason
  double nominal_dt_s = 0.0;  // the median interval
  long gaps = 0;              // intervals longer than 1.5 nominal intervals (kept, counted)
  std::vector<ImuTimeGap> long_gaps;  // intervals longer than ImuReadOptions::long_gap_factor nominal intervals
  double longest_gap_s = 0.0;
  long lines_with_data() const { return rows + dropped.total(); }
};

struct ImuReadOptions {
  int columns = 7;            // KF-GINS imudatalen: every data line must have exactly this many columns
  double rate_hz = 0.0;       // KF-GINS imudatarate: only checked against the median interval (a warning)
  double long_gap_factor = 10.0;
  // More dropped records than this fraction of the data lines is an error (a wrong file or a wrong imudatalen),
  // not something to count.
  double max_dropped_fraction = 0.10;
  std::string declared_by = "imudatalen";  // where `columns` came from, for messages
};

// Reads increments; dt_s of the first sample is taken from the second. Records with another column count than
// options.columns, non-numeric or non-finite fields, time going backwards or repeating, or a single time stamp
// far ahead of both neighbours are dropped and counted by reason (file:line of the first of each in the report
// and the log); too many of them (options.max_dropped_fraction) or no record at all raise InputError.
std::vector<ImuIncrement> read_kfgins_imu(const std::string& path, ImuReadReport* report = nullptr,
                                          const ImuReadOptions& options = {});
void write_kfgins_imu(const std::string& path, const std::vector<ImuIncrement>& imu);

struct GnssReadReport {
  long rows = 0;
  int columns = 0;  // 7 or 13: the first data line decides, the others must match
  DroppedRecords dropped;
};

// 7 or 13 columns (the first data line decides; lines with another count are dropped and counted, as are
// malformed lines, latitude beyond +-90 deg, non-positive std and time not increasing); too many drops
// (more than 10 % of the data lines) or no solution raise InputError.
std::vector<GnssFix> read_kfgins_gnss(const std::string& path, GnssReadReport* report = nullptr);
void write_kfgins_gnss(const std::string& path, const std::vector<GnssFix>& gnss, bool with_velocity);

// Strict (a .nav is our own output): any bad row raises InputError; the week must be an integer 0..9999.
std::vector<NavRecord> read_nav(const std::string& path);

// Streaming writer of .nav records (fast formatting; the estimator writes one line per IMU sample). A record with
// a non-finite field is refused with InputError naming the row and its time (the .nav layout has no token for
// "no value", and our own readers refuse nan): rows before it are kept. Write errors (a full disk) raise
// InputError at the write or at close(); call close() to know the file is complete.
class NavWriter {
 public:
  explicit NavWriter(const std::string& path);
  ~NavWriter();  // writes what is buffered (errors logged: close() is where they are reported)
  NavWriter(const NavWriter&) = delete;
  NavWriter& operator=(const NavWriter&) = delete;
  void write(const NavRecord& r);
  void close();

 private:
  void flush();
  OutputFile file_;
  std::vector<char> buf_;  // lines are formatted here and written in 1 MiB blocks
  size_t used_ = 0;
  long rows_ = 0;
};

}  // namespace ldv
