#pragma once
// Decoders for the u-blox UBX messages the GNSS link uses (u-blox 8 / M8 and F9 interface
// descriptions): NAV-PVT (position, velocity, time, fix and carrier solution status) and TIM-TP
// (the GPS time of the *next* time pulse). Raw fields keep the receiver's units; the converters
// produce SI GnssSolution / PpsTimeLabel.
#include <cstdint>
#include <optional>
#include <span>

#include "common/formats/gnss_solution.hpp"

namespace ldv::gnss {

constexpr std::uint8_t kUbxClassNav = 0x01, kUbxIdNavPvt = 0x07;
constexpr std::uint8_t kUbxClassTim = 0x0D, kUbxIdTimTp = 0x01;
constexpr std::size_t kUbxNavPvtBytes = 92, kUbxTimTpBytes = 16;

struct UbxNavPvt {
  std::uint32_t itow_ms = 0;  // GPS time of week of the navigation epoch (nominal, whole ms)
  std::uint16_t year = 0;     // UTC
  std::uint8_t month = 0, day = 0, hour = 0, minute = 0, second = 0;
  std::uint8_t valid = 0;     // bit0 validDate, bit1 validTime, bit2 fullyResolved
  std::uint32_t time_accuracy_ns = 0;
  std::int32_t nano_ns = 0;   // fraction of the UTC second, may be negative
  std::uint8_t fix_type = 0;  // 0 none, 1 dead reckoning, 2 2D, 3 3D, 4 GNSS + DR, 5 time only
  std::uint8_t flags = 0;     // bit0 gnssFixOK, bit1 diffSoln, bits 6-7 carrSoln (1 float, 2 fixed)
  std::uint8_t flags2 = 0;
  std::uint8_t num_sv = 0;
  std::int32_t lon_1e7deg = 0, lat_1e7deg = 0;
  std::int32_t height_mm = 0;  // above ellipsoid
  std::int32_t height_msl_mm = 0;
  std::uint32_t h_acc_mm = 0, v_acc_mm = 0;
  std::int32_t vel_n_mmps = 0, vel_e_mmps = 0, vel_d_mmps = 0;
  std::int32_t ground_speed_mmps = 0;
  std::int32_t head_motion_1e5deg = 0;
  std::uint32_t speed_acc_mmps = 0;
  std::uint32_t head_acc_1e5deg = 0;
  std::uint16_t pdop_001 = 0;
  std::uint8_t flags3 = 0;  // bit0 invalidLlh, bits 1-4 lastCorrectionAge (coded)

  bool gnss_fix_ok() const { return flags & 0x01; }
  bool differential() const { return flags & 0x02; }
  int carrier_solution() const { return (flags >> 6) & 0x03; }
  bool date_time_valid() const { return (valid & 0x03) == 0x03; }
  bool llh_invalid() const { return flags3 & 0x01; }
};

struct UbxTimTp {
  std::uint32_t tow_ms = 0;        // time of week of the next pulse, whole ms
  std::uint32_t tow_sub_ms = 0;    // its sub-millisecond part, units of 2^-32 ms
  std::int32_t quant_error_ps = 0; // quantisation error of the pulse
  std::uint16_t week = 0;
  std::uint8_t flags = 0;          // bit0 timeBase (0 GNSS, 1 UTC), bit1 UTC available, bit4 qErrInvalid
  std::uint8_t ref_info = 0;       // low nibble: GNSS of the time base (0 GPS, 1 GLONASS, 2 BeiDou, 3 Galileo)

  bool utc_time_base() const { return flags & 0x01; }
  bool quant_error_valid() const { return !(flags & 0x10); }
};

// nullopt if the payload is shorter than the message.
std::optional<UbxNavPvt> decode_nav_pvt(std::span<const std::uint8_t> payload);
std::optional<UbxTimTp> decode_tim_tp(std::span<const std::uint8_t> payload);

// NAV-PVT -> solution. nullopt without a usable fix (gnssFixOK clear, no 3D fix, invalid LLH) or
// without a valid date. The time is the exact epoch (UTC date-time + nanoseconds + GPS-UTC, the
// latter read off iTOW), not iTOW itself, which is rounded to the millisecond.
std::optional<GnssSolution> solution_from_nav_pvt(const UbxNavPvt& pvt);

// TIM-TP -> label of the next pulse. nullopt when the time base is not GPS time (UTC, or another
// GNSS's time scale): configure the receiver's time pulse to GPS (CFG-TP5 / CFG-TP-TIMEGRID_TP1).
std::optional<PpsTimeLabel> label_from_tim_tp(const UbxTimTp& tp);

}  // namespace ldv::gnss
