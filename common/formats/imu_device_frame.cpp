#include "common/formats/imu_device_frame.hpp"

#include <cmath>
#include <cstring>
#include <limits>

namespace ldv::imu_device {
namespace {
void put_u16(std::vector<uint8_t>& o, uint16_t v) {
  o.push_back(static_cast<uint8_t>(v));
  o.push_back(static_cast<uint8_t>(v >> 8));
}
void put_u32(std::vector<uint8_t>& o, uint32_t v) {
  for (int i = 0; i < 4; ++i) o.push_back(static_cast<uint8_t>(v >> (8 * i)));
}
uint16_t get_u16(const uint8_t* p) { return static_cast<uint16_t>(p[0] | (p[1] << 8)); }
uint32_t get_u32(const uint8_t* p) {
  return static_cast<uint32_t>(p[0]) | (static_cast<uint32_t>(p[1]) << 8) | (static_cast<uint32_t>(p[2]) << 16) |
         (static_cast<uint32_t>(p[3]) << 24);
}
constexpr size_t kImuPayload = 31, kPpsPayload = 6;

void finish(std::vector<uint8_t>& out, size_t start) {
  // CRC over type, length and payload (after the two sync bytes).
  const uint16_t crc = crc16_ccitt(out.data() + start + 2, out.size() - start - 2);
  put_u16(out, crc);
}
}  // namespace

uint16_t crc16_ccitt(const uint8_t* data, size_t n) {
  uint16_t crc = 0xFFFF;
  for (size_t i = 0; i < n; ++i) {
    crc ^= static_cast<uint16_t>(data[i]) << 8;
    for (int b = 0; b < 8; ++b) crc = (crc & 0x8000) ? static_cast<uint16_t>((crc << 1) ^ 0x1021) : static_cast<uint16_t>(crc << 1);
  }
  return crc;
}

void append_frame(std::vector<uint8_t>& out, const ImuSampleFrame& f) {
  const size_t start = out.size();
  out.insert(out.end(), {kSync0, kSync1, kTypeImuSample, static_cast<uint8_t>(kImuPayload)});
  put_u32(out, f.counter);
  put_u16(out, f.sequence);
  for (int32_t v : f.dtheta_lsb) put_u32(out, static_cast<uint32_t>(v));
  for (int32_t v : f.dvel_lsb) put_u32(out, static_cast<uint32_t>(v));
  out.push_back(f.status);
  finish(out, start);
}

void append_frame(std::vector<uint8_t>& out, const PpsLatchFrame& f) {
  const size_t start = out.size();
  out.insert(out.end(), {kSync0, kSync1, kTypePpsLatch, static_cast<uint8_t>(kPpsPayload)});
  put_u32(out, f.counter);
  put_u16(out, f.sequence);
  finish(out, start);
}

std::vector<Frame> FrameDecoder::push(const uint8_t* data, size_t n) {
  buffer_.insert(buffer_.end(), data, data + n);
  std::vector<Frame> frames;
  size_t i = 0;
  while (true) {
    // Find sync.
    while (i + 1 < buffer_.size() && !(buffer_[i] == kSync0 && buffer_[i + 1] == kSync1)) {
      ++i;
      ++skipped_bytes_;
    }
    if (i + 4 > buffer_.size()) break;
    const uint8_t type = buffer_[i + 2];
    const size_t len = buffer_[i + 3];
    const bool known = (type == kTypeImuSample && len == kImuPayload) || (type == kTypePpsLatch && len == kPpsPayload);
    if (!known) {  // not a frame start after all
      ++i;
      ++skipped_bytes_;
      continue;
    }
    if (i + 4 + len + 2 > buffer_.size()) break;
    const uint8_t* p = buffer_.data() + i;
    if (crc16_ccitt(p + 2, 2 + len) != get_u16(p + 4 + len)) {
      ++crc_errors_;
      ++i;
      ++skipped_bytes_;
      continue;
    }
    const uint8_t* pl = p + 4;
    if (type == kTypeImuSample) {
      ImuSampleFrame f;
      f.counter = get_u32(pl);
      f.sequence = get_u16(pl + 4);
      for (int k = 0; k < 3; ++k) f.dtheta_lsb[k] = static_cast<int32_t>(get_u32(pl + 6 + 4 * k));
      for (int k = 0; k < 3; ++k) f.dvel_lsb[k] = static_cast<int32_t>(get_u32(pl + 18 + 4 * k));
      f.status = pl[30];
      frames.emplace_back(f);
    } else {
      frames.emplace_back(PpsLatchFrame{get_u32(pl), get_u16(pl + 4)});
    }
    i += 4 + len + 2;
  }
  buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<long>(std::min(i, buffer_.size())));
  return frames;
}

std::array<int32_t, 3> IncrementQuantizer::quantize(const double v[3], double lsb, std::array<double, 3>& rest,
                                                    bool& over) {
  std::array<int32_t, 3> out{};
  constexpr double kMax = std::numeric_limits<int32_t>::max();
  for (int i = 0; i < 3; ++i) {
    const double want = v[i] / lsb + rest[i];
    double q = std::round(want);
    if (std::abs(q) > kMax) {
      q = std::copysign(kMax, q);
      over = true;
      rest[i] = 0.0;  // the excess is lost, as in a saturated sensor
    } else {
      rest[i] = want - q;
    }
    out[i] = static_cast<int32_t>(q);
  }
  return out;
}

}  // namespace ldv::imu_device
