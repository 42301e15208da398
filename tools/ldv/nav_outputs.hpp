#pragma once
// The files `ldv nav` and `ldv smooth` write: FILE.nav (KF-GINS layout, every IMU sample), FILE_std.txt (std
// and effect estimates at --std-rate), FILE_innovations.txt (every measurement), and for a smoothed run
// FILE_separation.txt (forward minus smoothed, with its expected 1-sigma).
#include <functional>
#include <string>
#include <vector>

#include "common/formats/kfgins_files.hpp"
#include "common/io/output_file.hpp"
#include "estimator/smooth/rts_recorder.hpp"
#include "estimator/state/state_layout.hpp"

namespace ldv::est {
class NavFilter;  // nav_filter.hpp (read, never held)
}

namespace ldv::cli {

// Writes columns with fixed decimals fast, in 256 KiB blocks; write errors raise InputError (at a block or at
// close()).
class TextOut {
 public:
  TextOut(const std::string& path, const std::string& header);
  ~TextOut();  // writes what is buffered (errors logged: close() is where they are reported)
  void close();
  void num(double v, int decimals);
  void text(const char* s);
  void end_line();

 private:
  void flush();
  OutputFile f_;
  std::vector<char> buf_;
  size_t n_ = 0, line_start_ = 0;
};

// FILE.nav -> FILE (the other outputs are named after it).
std::string output_base(const std::string& nav_path);
// KF-GINS's .nav row of a state (yaw in [0, 360)), stamped t_gnss_s (NavFilter::gnss_time_s).
NavRecord nav_record(const est::NavState& s, int week, double t_gnss_s);

// The three outputs of a filter run: .nav at every IMU sample, std rows at std_rate_hz, every innovation.
class NavOutputs {
 public:
  NavOutputs(const std::string& nav_path, const est::NavFilter& f, double std_rate_hz);
  void epoch(const est::NavFilter& f, int week);
  void innovation(const est::InnovationRecord& r);
  void close();  // a full disk is an error here, not a truncated file and exit 0
  // Epochs whose time was not after the row written last (not written: the file's times only increase).
  long rows_not_advancing() const { return rows_not_advancing_; }

 private:
  NavWriter nav_;
  TextOut std_, innov_;
  double std_period_;
  double next_std_t_ = -1e300;
  double last_row_t_s_ = -1e300;
  long rows_not_advancing_ = 0;
};

// The start of FILE_separation.txt's header (how ldv nav recognises an earlier ldv smooth's file).
inline constexpr const char* kSeparationHeaderStart = "# week sow sep_n sep_e sep_d";

// A smoothed run's files: FILE.nav, FILE_std.txt (the smoothed std and effect estimates, as NavOutputs writes
// them) and FILE_separation.txt at std_rate_hz.
// gyro_quantization_rad: the gyros' Q, added to the smoothed attitude sigma as the forward filter's (it cancels in the
// separation: forward and smoothed attitude carry the same white angle error).
// time_offset_s: the forward filter's final time_offset, added to every row's time (NavFilter::gnss_time_s; a
// constant state's smoothed value is its last filtered one).
void write_smoothed(const est::SmoothedRun& run, const est::StateLayout& layout, const std::string& nav_path,
                    double std_rate_hz, const Vec3& gyro_quantization_rad, double time_offset_s,
                    const std::function<void(double)>& progress = {});

}  // namespace ldv::cli
