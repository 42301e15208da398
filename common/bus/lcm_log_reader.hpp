#pragma once
// Reads an LCM event log (the lcm-logger / ldv_logger format) without liblcm's reader. Why our own:
// liblcm 1.3.1's lcm_eventlog_read_next_event trusts the event's length fields and allocates and reads
// whatever they say, so one corrupted length (2 GB) crashes `ldv export` and `ldv nav --lcm-log`.
// The format (big-endian): sync word 0xEDA1DA01, int64 event number, int64 receive time [us since the
// Unix epoch], int32 channel length, int32 data length, channel bytes, data bytes.
// Here every length is checked against the bytes left in the file and sane limits; a corrupt event is
// counted and the reader resynchronises on the next sync word, so nothing after it is lost.
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

namespace ldv {

struct LcmLogEvent {
  int64_t event_number = 0;
  int64_t timestamp_us = 0;  // the logger's receive time
  std::string channel;
  std::vector<uint8_t> data;
};

class LcmLogReader {
 public:
  static constexpr uint32_t kSyncWord = 0xEDA1DA01u;
  static constexpr int32_t kMaxChannelBytes = 256;     // LCM allows 63; a little slack for other tools
  static constexpr int32_t kMaxEventBytes = 64 << 20;  // far above any LCM message (UDP limit ~ 64 kB)

  // Throws InputError naming the file when it cannot be opened or is not a regular file.
  explicit LcmLogReader(const std::string& path);

  // The next intact event; false at the end of the file.
  bool next(LcmLogEvent& event);

  long corrupt_events() const { return corrupt_; }      // bad header or lengths: skipped, resynchronised
  long truncated_events() const { return truncated_; }  // the last event cut short (a logger killed mid-write)
  const std::string& path() const { return path_; }

 private:
  bool resync();  // moves to the next sync word after the current position

  std::string path_;
  std::ifstream in_;
  int64_t size_bytes_ = 0;
  long corrupt_ = 0, truncated_ = 0;
};

}  // namespace ldv
