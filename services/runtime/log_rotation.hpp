#pragma once
// The bus logger's file handling (ldv_logger, services/runtime/bus_logger.cpp): LCM log files that
// rotate by size or age, and a retention that deletes the oldest completed files by total size, age
// or free disk space, so a vehicle that records for weeks never fills its disk. The file being
// written is never deleted.
//
// Naming: for a base path /var/log/ldvnav/ldvnav.lcmlog the files are
//   /var/log/ldvnav/ldvnav.000042.20250131T120000Z.lcmlog
// the index (6+ digits) grows across restarts (the next index after the highest on disk), so the
// order of the files does not depend on the host clock (which may jump when it is disciplined after
// boot); the UTC time of the file's opening is only for people. Without rotation (max_file_mb and
// max_file_min both 0) the base path itself is written, overwritten at start, as lcm-logger -f does.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace lcm {
class LogFile;
}

namespace ldv {

struct LogRotationOptions {
  std::string path;           // base path (see above)
  double max_file_mb = 0;     // start the next file when the current one reaches this size; 0: no size limit
  double max_file_min = 0;    // start the next file when the current one is this old; 0: no age limit
  double max_total_mb = 0;    // delete the oldest completed files while all files together exceed this; 0: no limit
  double max_age_h = 0;       // delete completed files last written longer ago than this; 0: keep
  double min_free_mb = 0;     // delete the oldest completed files while the file system has less free space; 0: off
  bool rotating() const { return max_file_mb > 0 || max_file_min > 0; }
  // Throws std::invalid_argument on a contradiction (retention without rotation, negative values).
  void validate() const;
};

class RotatingLogWriter {
 public:
  struct LogFileInfo {
    std::string path;
    int64_t index = -1;
    uint64_t bytes = 0;
    double mtime_s = 0;  // last write, seconds since the Unix epoch
  };

  // now_s: the clock for file ages and names (host_time_s in the logger; tests pass their own).
  explicit RotatingLogWriter(LogRotationOptions options, std::function<double()> now_s);
  ~RotatingLogWriter();
  RotatingLogWriter(const RotatingLogWriter&) = delete;
  RotatingLogWriter& operator=(const RotatingLogWriter&) = delete;

  // Appends one event (rotating first if the current file is full or old). False on a write error.
  bool write(const std::string& channel, const uint8_t* data, int size, int64_t timestamp_us);
  void flush();
  // Applies the retention rules now (the logger calls it every few seconds and after each rotation).
  void enforce_retention();

  const std::string& current_path() const { return current_path_; }
  uint64_t current_bytes() const { return current_bytes_; }
  // This logger's files on disk (matching the base path's naming), oldest (lowest index) first.
  std::vector<LogFileInfo> files() const;
  int64_t files_deleted() const { return files_deleted_; }
  int64_t rotations() const { return rotations_; }

 private:
  void open_next();

  LogRotationOptions o_;
  std::function<double()> now_s_;
  std::string dir_, stem_, ext_;
  std::unique_ptr<lcm::LogFile> log_;
  std::string current_path_;
  int64_t current_index_ = -1;
  double opened_s_ = 0;
  uint64_t current_bytes_ = 0;  // counted, not ftell'd: no syscall per event
  int64_t event_number_ = 0;
  int64_t files_deleted_ = 0;
  int64_t rotations_ = 0;
};

}  // namespace ldv
