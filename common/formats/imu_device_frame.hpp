#pragma once
// The ldvnav IMU time-stamp-unit byte protocol (the simulator writes it, imu_acq decodes it).
// Every frame, little endian:
//   0xA5 0x5A | type u8 | payload length u8 | payload | CRC-16/CCITT-FALSE (u16, over type..payload)
// type 0x01 IMU sample (31 bytes):  counter u32 (free-running oscillator latched at the sample instant),
//   sequence u16 (wraps), dtheta x y z i32 [LSB 1e-9 rad], dvel x y z i32 [LSB 1e-9 m/s], status u8
//   (bit 0: over-range, the value saturated). Increments over (previous sample, this sample], body
//   front-right-down; rounding residuals are carried to the next sample, so sums never drift.
// type 0x02 PPS latch (6 bytes): counter u32 latched at the PPS edge, sequence u16 (wraps).
// The GPS second of each PPS edge comes from the receiver's time message (NMEA ZDA), not from here.
#include <array>
#include <cstddef>
#include <cstdint>
#include <variant>
#include <vector>

namespace ldv::imu_device {

constexpr uint8_t kSync0 = 0xA5, kSync1 = 0x5A;
constexpr uint8_t kTypeImuSample = 0x01, kTypePpsLatch = 0x02;
constexpr double kDthetaLsb_rad = 1e-9;
constexpr double kDvelLsb_mps = 1e-9;
constexpr uint8_t kStatusOverRange = 0x01;

struct ImuSampleFrame {
  uint32_t counter = 0;
  uint16_t sequence = 0;
  std::array<int32_t, 3> dtheta_lsb{}, dvel_lsb{};
  uint8_t status = 0;
};

struct PpsLatchFrame {
  uint32_t counter = 0;
  uint16_t sequence = 0;
};

using Frame = std::variant<ImuSampleFrame, PpsLatchFrame>;

// CRC-16/CCITT-FALSE: poly 0x1021, init 0xFFFF, no reflection, no final xor ("123456789" -> 0x29B1).
uint16_t crc16_ccitt(const uint8_t* data, size_t n);

void append_frame(std::vector<uint8_t>& out, const ImuSampleFrame& f);
void append_frame(std::vector<uint8_t>& out, const PpsLatchFrame& f);

// Incremental decoder: push any chunk of bytes, get the complete frames; resynchronises on the sync
// bytes after garbage or a CRC error.
class FrameDecoder {
 public:
  std::vector<Frame> push(const uint8_t* data, size_t n);
  uint64_t crc_errors() const { return crc_errors_; }
  uint64_t skipped_bytes() const { return skipped_bytes_; }

 private:
  std::vector<uint8_t> buffer_;
  uint64_t crc_errors_ = 0, skipped_bytes_ = 0;
};

// Quantises increments to the frame's LSB with the residual carried forward (as a real device does).
class IncrementQuantizer {
 public:
  // Returns the integer counts; sets over_range when a value saturated.
  std::array<int32_t, 3> dtheta(const double v_rad[3], bool& over_range) { return quantize(v_rad, kDthetaLsb_rad, rest_theta_, over_range); }
  std::array<int32_t, 3> dvel(const double v_mps[3], bool& over_range) { return quantize(v_mps, kDvelLsb_mps, rest_vel_, over_range); }

 private:
  static std::array<int32_t, 3> quantize(const double v[3], double lsb, std::array<double, 3>& rest, bool& over);
  std::array<double, 3> rest_theta_{}, rest_vel_{};
};

}  // namespace ldv::imu_device
