#include "common/bus/lcm_log_reader.hpp"

#include <filesystem>

#include "common/io/input_error.hpp"

namespace ldv {
namespace {

uint64_t big_endian(const uint8_t* p, int bytes) {
  uint64_t v = 0;
  for (int i = 0; i < bytes; ++i) v = (v << 8) | p[i];
  return v;
}

constexpr int kHeaderBytes = 4 + 8 + 8 + 4 + 4;

}  // namespace

LcmLogReader::LcmLogReader(const std::string& path) : path_(path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(path, 0, "not a regular file (an LCM log was expected)");
  size_bytes_ = static_cast<int64_t>(std::filesystem::file_size(path, ec));
  in_.open(path, std::ios::binary);
  if (ec || !in_) throw InputError(path, 0, "cannot open LCM log file");
}

bool LcmLogReader::resync() {
  // Search byte by byte for the sync word; the window holds the last four bytes read.
  uint32_t window = 0;
  int have = 0;
  char c;
  while (in_.get(c)) {
    window = (window << 8) | static_cast<uint8_t>(c);
    if (++have >= 4 && window == kSyncWord) {
      in_.seekg(-4, std::ios::cur);
      return true;
    }
  }
  return false;
}

bool LcmLogReader::next(LcmLogEvent& ev) {
  for (;;) {
    const int64_t start = in_.tellg();
    if (start < 0 || start >= size_bytes_) return false;
    uint8_t h[kHeaderBytes];
    if (!in_.read(reinterpret_cast<char*>(h), kHeaderBytes)) {
      ++truncated_;
      return false;
    }
    const uint32_t sync = static_cast<uint32_t>(big_endian(h, 4));
    const int64_t channel_bytes = static_cast<int32_t>(big_endian(h + 20, 4));
    const int64_t data_bytes = static_cast<int32_t>(big_endian(h + 24, 4));
    const int64_t end = start + kHeaderBytes + channel_bytes + data_bytes;
    const bool lengths_ok = sync == kSyncWord && channel_bytes > 0 && channel_bytes <= kMaxChannelBytes &&
                            data_bytes >= 0 && data_bytes <= kMaxEventBytes;
    // An event is intact when its lengths are sane and it ends at the end of the file or at the next
    // sync word: a wrong length that is still "sane" cannot swallow the events after it.
    bool intact = lengths_ok && end <= size_bytes_;
    if (intact && end < size_bytes_) {
      uint8_t next_sync[4] = {0, 0, 0, 0};
      in_.seekg(end);
      in_.read(reinterpret_cast<char*>(next_sync), 4);
      intact = in_.gcount() < 4 || big_endian(next_sync, 4) == kSyncWord;
      in_.clear();
      in_.seekg(start + kHeaderBytes);
    }
    if (!intact) {
      in_.clear();
      in_.seekg(start + 1);
      if (!resync()) {  // nothing intact after it: the file ends with a cut or corrupt event
        ++(lengths_ok && end > size_bytes_ ? truncated_ : corrupt_);
        return false;
      }
      ++corrupt_;
      continue;
    }
    ev.event_number = static_cast<int64_t>(big_endian(h + 4, 8));
    ev.timestamp_us = static_cast<int64_t>(big_endian(h + 12, 8));
    ev.channel.resize(static_cast<size_t>(channel_bytes));
    ev.data.resize(static_cast<size_t>(data_bytes));
    in_.read(ev.channel.data(), channel_bytes);
    if (data_bytes > 0) in_.read(reinterpret_cast<char*>(ev.data.data()), data_bytes);
    if (!in_) {
      ++truncated_;
      return false;
    }
    return true;
  }
}

}  // namespace ldv
