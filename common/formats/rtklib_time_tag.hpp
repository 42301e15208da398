#pragma once
// RTKLIB time-tag files (`<stream file>.tag`, written by str2str/rtkrcv with the -t option): a 60-byte
// text header ("TIMETAG RTKLIB EX..."), uint32 tick_f [ms, host tick at file start], uint32 time
// [Unix-style seconds in GPST], double fraction [s], then (uint32 tick_ms since file start,
// uint32 file_pos) pairs, little endian. RTKLIB writes a pair after each chunk it stored (stream.c, writefile:
// the file position after the write), so the bytes before file_pos, from the previous pair's file_pos on, were
// received at tick_ms.
#include <cstdint>
#include <string>
#include <vector>

#include "common/time/gps_time.hpp"

namespace ldv {

struct RtklibTimeTag {
  double start_gps_s = 0.0;  // GPS seconds since the GPS epoch at tick 0
  struct Entry {
    uint32_t tick_ms;
    uint32_t file_pos;
  };
  std::vector<Entry> entries;

  // Host reception time (GPS seconds since the GPS epoch) of the byte at file_pos: the tick of the first chunk
  // that ends beyond it (past the last pair: the last tick).
  double reception_gps_s(uint64_t file_pos) const;
};

RtklibTimeTag read_rtklib_time_tag(const std::string& path);

}  // namespace ldv
