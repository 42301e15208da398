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

namespace ldv {

struct ImuReadReport {
  long rows = 0;
  long skipped_duplicates = 0;  // identical time stamps (dropped, counted)
  long gaps = 0;                // intervals longer than 1.5 nominal intervals (kept, counted)
};

// Reads increments; dt_s of the first sample is taken from the second. Throws InputError on time going
// backwards, non-numeric or non-finite fields, fewer than 7 columns, or an empty file.
std::vector<ImuIncrement> read_kfgins_imu(const std::string& path, ImuReadReport* report = nullptr);
void write_kfgins_imu(const std::string& path, const std::vector<ImuIncrement>& imu);

std::vector<GnssFix> read_kfgins_gnss(const std::string& path);
void write_kfgins_gnss(const std::string& path, const std::vector<GnssFix>& gnss, bool with_velocity);

std::vector<NavRecord> read_nav(const std::string& path);

// Streaming writer of .nav records (fast formatting; the estimator writes one line per IMU sample).
class NavWriter {
 public:
  explicit NavWriter(const std::string& path);
  ~NavWriter();
  NavWriter(const NavWriter&) = delete;
  NavWriter& operator=(const NavWriter&) = delete;
  void write(const NavRecord& r);

 private:
  void flush();
  std::FILE* file_;
  std::string path_;
  std::vector<char> buf_;  // lines are formatted here and written in 1 MiB blocks
  size_t used_ = 0;
};

}  // namespace ldv
