#include "services/imu_acq/protocols/gx2_frame.hpp"

#include <bit>
#include <cstring>

namespace ldv::imu::gx2 {
namespace {
std::uint32_t get_u32_be(const std::uint8_t* p) {
  return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) | p[3];
}
float get_f32_be(const std::uint8_t* p) { return std::bit_cast<float>(get_u32_be(p)); }
void put_u32_be(std::vector<std::uint8_t>& o, std::uint32_t v) {
  for (int s = 24; s >= 0; s -= 8) o.push_back(static_cast<std::uint8_t>(v >> s));
}
std::uint16_t sum16(std::span<const std::uint8_t> bytes) {
  std::uint16_t s = 0;
  for (std::uint8_t b : bytes) s = static_cast<std::uint16_t>(s + b);
  return s;
}
}  // namespace

std::optional<std::size_t> record_bytes(std::uint8_t command) {
  switch (command) {
    case kAccelRate: return 31;
    case kDeltaAngleVelocity: return 31;
    case kAccelRateOrientation: return 67;
    case kAccelRateMag: return 43;
    case kAccelRateMagOrientation: return 79;
    default: return std::nullopt;
  }
}

std::optional<Record> parse_record(std::span<const std::uint8_t> bytes) {
  if (bytes.empty()) return std::nullopt;
  const auto n = record_bytes(bytes[0]);
  if (!n || bytes.size() < *n) return std::nullopt;
  const std::uint8_t* p = bytes.data();
  const std::uint16_t checksum = static_cast<std::uint16_t>((p[*n - 2] << 8) | p[*n - 1]);
  if (sum16(bytes.first(*n - 2)) != checksum) return std::nullopt;
  Record r;
  r.command = p[0];
  // Every record starts with two vectors; the rest (matrix, magnetometer) is not needed here.
  // On the wire: C3 = delta angle then delta velocity; the others = acceleration then rate.
  std::array<float, 3> a{}, b{};
  for (int i = 0; i < 3; ++i) {
    a[i] = get_f32_be(p + 1 + 4 * i);
    b[i] = get_f32_be(p + 13 + 4 * i);
  }
  if (r.is_delta()) {
    r.first = a;   // delta angle
    r.second = b;  // delta velocity
  } else {
    r.first = b;   // angular rate
    r.second = a;  // acceleration
  }
  r.timer = get_u32_be(p + *n - 6);
  return r;
}

std::vector<std::uint8_t> encode_record(std::uint8_t command, const std::array<float, 3>& first,
                                        const std::array<float, 3>& second, std::uint32_t timer) {
  const auto n = record_bytes(command);
  if (!n) return {};
  std::vector<std::uint8_t> o{command};
  for (float v : first) put_u32_be(o, std::bit_cast<std::uint32_t>(v));
  for (float v : second) put_u32_be(o, std::bit_cast<std::uint32_t>(v));
  o.resize(*n - 6, 0);  // orientation matrix / magnetometer: zero
  put_u32_be(o, timer);
  const std::uint16_t s = sum16(o);
  o.push_back(static_cast<std::uint8_t>(s >> 8));
  o.push_back(static_cast<std::uint8_t>(s));
  return o;
}

std::vector<std::uint8_t> start_continuous_command(std::uint8_t record_command) {
  return {0xC4, 0xC1, 0x29, record_command};
}

}  // namespace ldv::imu::gx2
