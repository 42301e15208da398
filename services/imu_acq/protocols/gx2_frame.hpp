#pragma once
// MicroStrain 3DM-GX2 binary data messages (3DM-GX2 Data Communications Protocol). A reply or a
// continuous-mode record is the command byte, big-endian IEEE-754 floats, a big-endian 32-bit
// timer and a big-endian 16-bit checksum (the sum of all preceding bytes). The records decoded:
//   0xC2 acceleration [g] and angular rate [rad/s]                          31 bytes
//   0xC3 delta angle [rad] and delta velocity [g s]                          31 bytes
//   0xC8 acceleration, angular rate, orientation matrix                      67 bytes
//   0xCB acceleration, angular rate, magnetometer                            43 bytes
//   0xCC acceleration, angular rate, magnetometer, orientation matrix        79 bytes
// The timer counts at 19 660 800 Hz on the GX2 (62 500 Hz on the GX3: configurable).
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace ldv::imu::gx2 {

constexpr std::uint8_t kAccelRate = 0xC2, kDeltaAngleVelocity = 0xC3, kAccelRateOrientation = 0xC8,
                       kAccelRateMag = 0xCB, kAccelRateMagOrientation = 0xCC;
constexpr double kTimerHz = 19660800.0;
constexpr double kStandardGravity_mps2 = 9.80665;  // the device's "g"

// Record length in bytes for a known record command, nullopt otherwise.
std::optional<std::size_t> record_bytes(std::uint8_t command);

struct Record {
  std::uint8_t command = 0;
  // 0xC3: delta angle [rad] and delta velocity [g s]; otherwise angular rate [rad/s] and
  // acceleration [g].
  std::array<float, 3> first{}, second{};
  std::uint32_t timer = 0;
  bool is_delta() const { return command == kDeltaAngleVelocity; }
};

// A checksum-verified record of record_bytes(bytes[0]) bytes; nullopt if unknown or corrupt.
std::optional<Record> parse_record(std::span<const std::uint8_t> bytes);

// Builds a record (tests, simulators). For 0xC2/0xC8/0xCB/0xCC `first` is the acceleration and
// `second` the angular rate, as on the wire; matrix and magnetometer fields are zero.
std::vector<std::uint8_t> encode_record(std::uint8_t command, const std::array<float, 3>& first,
                                        const std::array<float, 3>& second, std::uint32_t timer);

// "Set continuous mode" for a record command: the device then streams that record.
std::vector<std::uint8_t> start_continuous_command(std::uint8_t record_command);

}  // namespace ldv::imu::gx2
