#include "common/formats/rtklib_time_tag.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>

#include "common/io/input_error.hpp"
#include "common/io/text_file_lines.hpp"

namespace ldv {

RtklibTimeTag read_rtklib_time_tag(const std::string& path) {
  // Bounded (a device or a wrong huge file is refused): 256 MiB is 33 million tags, years of 1 Hz chunks.
  const std::string bytes = read_small_text_file(path, static_cast<size_t>(256) << 20);
  constexpr size_t kHeader = 60, kFixed = kHeader + 4 + 4 + 8;
  if (bytes.size() < kFixed || std::strncmp(bytes.data(), "TIMETAG RTKLIB", 14) != 0)
    throw InputError(path, 0, "not an RTKLIB time-tag file (expected the 'TIMETAG RTKLIB' header and 76 bytes)");
  if ((bytes.size() - kFixed) % 8 != 0)
    throw InputError(path, 0, "truncated RTKLIB time-tag file: " + std::to_string((bytes.size() - kFixed) % 8) +
                                  " trailing bytes after the last (tick, position) pair");
  uint32_t tick_f = 0, time_s = 0;
  double fraction = 0.0;
  std::memcpy(&tick_f, bytes.data() + kHeader, 4);
  std::memcpy(&time_s, bytes.data() + kHeader + 4, 4);
  std::memcpy(&fraction, bytes.data() + kHeader + 8, 8);
  // RTKLIB writes the fraction of the start second (stream.c: time.sec): a NaN or a value outside [0, 1) is a
  // corrupted header, and its NaN would make every IMU time NaN far from here.
  if (!std::isfinite(fraction) || fraction < 0.0 || fraction >= 1.0)
    throw InputError(path, 0, "time-tag header: the start time's fraction of a second (bytes 68-75) is " +
                                  std::to_string(fraction) + ", expected a number in [0, 1)");
  RtklibTimeTag tag;
  tag.start_gps_s = static_cast<double>(time_s) - kGpsEpochInUnixSeconds + fraction;
  for (size_t off = kFixed; off + 8 <= bytes.size(); off += 8) {
    RtklibTimeTag::Entry e{};
    std::memcpy(&e.tick_ms, bytes.data() + off, 4);
    std::memcpy(&e.file_pos, bytes.data() + off + 4, 4);
    if (!tag.entries.empty() && (e.file_pos < tag.entries.back().file_pos || e.tick_ms < tag.entries.back().tick_ms))
      throw InputError(path, 0, "time-tag entry " + std::to_string(tag.entries.size() + 1) +
                                    " goes backwards in tick or file position");
    tag.entries.push_back(e);
  }
  if (tag.entries.empty()) throw InputError(path, 0, "time-tag file has no (tick, position) entries");
  return tag;
}

double RtklibTimeTag::reception_gps_s(uint64_t file_pos) const {
  // The first entry whose chunk ends beyond file_pos received that byte (each entry holds the position after
  // its chunk; read as the chunk's start, every byte was placed one chunk early: 15 ms on the walk's IMU log).
  auto it = std::upper_bound(entries.begin(), entries.end(), file_pos,
                             [](uint64_t pos, const Entry& e) { return pos < e.file_pos; });
  const Entry& e = it == entries.end() ? entries.back() : *it;
  return start_gps_s + e.tick_ms * 1e-3;
}

}  // namespace ldv
