#include "common/formats/ubx_messages.hpp"

#include <cmath>
#include <numbers>

namespace ldv::gnss {
namespace {
constexpr double kDegToRad = std::numbers::pi / 180.0;

// Little-endian field readers at a byte offset (the payload length is checked by the caller).
template <typename T>
T read_le(std::span<const std::uint8_t> p, std::size_t offset) {
  std::uint64_t v = 0;
  for (std::size_t k = 0; k < sizeof(T); ++k) v |= std::uint64_t{p[offset + k]} << (8 * k);
  return static_cast<T>(v);
}
}  // namespace

std::optional<UbxNavPvt> decode_nav_pvt(std::span<const std::uint8_t> p) {
  if (p.size() < kUbxNavPvtBytes) return std::nullopt;
  UbxNavPvt m;
  m.itow_ms = read_le<std::uint32_t>(p, 0);
  m.year = read_le<std::uint16_t>(p, 4);
  m.month = p[6];
  m.day = p[7];
  m.hour = p[8];
  m.minute = p[9];
  m.second = p[10];
  m.valid = p[11];
  m.time_accuracy_ns = read_le<std::uint32_t>(p, 12);
  m.nano_ns = read_le<std::int32_t>(p, 16);
  m.fix_type = p[20];
  m.flags = p[21];
  m.flags2 = p[22];
  m.num_sv = p[23];
  m.lon_1e7deg = read_le<std::int32_t>(p, 24);
  m.lat_1e7deg = read_le<std::int32_t>(p, 28);
  m.height_mm = read_le<std::int32_t>(p, 32);
  m.height_msl_mm = read_le<std::int32_t>(p, 36);
  m.h_acc_mm = read_le<std::uint32_t>(p, 40);
  m.v_acc_mm = read_le<std::uint32_t>(p, 44);
  m.vel_n_mmps = read_le<std::int32_t>(p, 48);
  m.vel_e_mmps = read_le<std::int32_t>(p, 52);
  m.vel_d_mmps = read_le<std::int32_t>(p, 56);
  m.ground_speed_mmps = read_le<std::int32_t>(p, 60);
  m.head_motion_1e5deg = read_le<std::int32_t>(p, 64);
  m.speed_acc_mmps = read_le<std::uint32_t>(p, 68);
  m.head_acc_1e5deg = read_le<std::uint32_t>(p, 72);
  m.pdop_001 = read_le<std::uint16_t>(p, 76);
  m.flags3 = p[78];
  return m;
}

std::optional<UbxTimTp> decode_tim_tp(std::span<const std::uint8_t> p) {
  if (p.size() < kUbxTimTpBytes) return std::nullopt;
  UbxTimTp m;
  m.tow_ms = read_le<std::uint32_t>(p, 0);
  m.tow_sub_ms = read_le<std::uint32_t>(p, 4);
  m.quant_error_ps = read_le<std::int32_t>(p, 8);
  m.week = read_le<std::uint16_t>(p, 12);
  m.flags = p[14];
  m.ref_info = p[15];
  return m;
}

std::optional<GnssSolution> solution_from_nav_pvt(const UbxNavPvt& pvt) {
  const bool three_d = pvt.fix_type == 3 || pvt.fix_type == 4;
  if (!pvt.gnss_fix_ok() || !three_d || pvt.llh_invalid() || !pvt.date_time_valid()) return std::nullopt;

  // NAV-PVT has no week number and iTOW is the nominal epoch rounded to the millisecond; the UTC
  // date-time with its nanoseconds is the exact epoch. GPS - UTC is the whole number of seconds
  // between iTOW and the UTC time of week, so no leap-second table is needed; the week comes from
  // the date, corrected when the two straddle a week boundary.
  const GpsTime utc = gps_from_calendar({pvt.year, pvt.month, pvt.day, pvt.hour, pvt.minute, double(pvt.second)});
  const double utc_sow_s = utc.sow_s + pvt.nano_ns * 1e-9;
  double gps_minus_utc_s = std::round(pvt.itow_ms * 1e-3 - utc_sow_s);
  if (gps_minus_utc_s > kSecondsPerWeek / 2) {
    gps_minus_utc_s -= kSecondsPerWeek;
  } else if (gps_minus_utc_s < -kSecondsPerWeek / 2) {
    gps_minus_utc_s += kSecondsPerWeek;
  }
  GpsTime t{utc.week, utc_sow_s + gps_minus_utc_s};
  if (t.sow_s >= kSecondsPerWeek) {
    t.sow_s -= kSecondsPerWeek;
    ++t.week;
  } else if (t.sow_s < 0.0) {
    t.sow_s += kSecondsPerWeek;
    --t.week;
  }

  GnssSolution s;
  s.time = t;
  GnssFix& f = s.fix;
  f.t_s = t.sow_s;
  f.pos = {pvt.lat_1e7deg * 1e-7 * kDegToRad, pvt.lon_1e7deg * 1e-7 * kDegToRad, pvt.height_mm * 1e-3};
  switch (pvt.carrier_solution()) {
    case 2: f.quality = GnssQuality::kFixed; break;
    case 1: f.quality = GnssQuality::kFloat; break;
    default: f.quality = pvt.differential() ? GnssQuality::kDgps : GnssQuality::kSingle;
  }
  f.num_sats = pvt.num_sv;
  // hAcc is one horizontal figure: split it equally over north and east.
  const double h_std_m = pvt.h_acc_mm * 1e-3 / std::numbers::sqrt2, v_std_m = pvt.v_acc_mm * 1e-3;
  s.pos_cov_ned_m2 = Vec3(h_std_m * h_std_m, h_std_m * h_std_m, v_std_m * v_std_m).asDiagonal();
  sync_std_from_cov(s);
  f.has_velocity = true;
  f.vel_n_mps = Vec3(pvt.vel_n_mmps, pvt.vel_e_mmps, pvt.vel_d_mmps) * 1e-3;
  f.vel_std_n_mps = Vec3::Constant(pvt.speed_acc_mmps * 1e-3);
  f.age_s = 0.0;  // NAV-PVT only has a coded age range (flags3); NAV-RELPOSNED/NMEA give it
  f.ratio = 0.0;
  return s;
}

std::optional<PpsTimeLabel> label_from_tim_tp(const UbxTimTp& tp) {
  const int time_gnss = tp.ref_info & 0x0f;
  if (tp.utc_time_base() || time_gnss != 0) return std::nullopt;
  PpsTimeLabel label;
  label.pulse_time.week = tp.week;
  label.pulse_time.sow_s = tp.tow_ms * 1e-3 + tp.tow_sub_ms * (1e-3 / 4294967296.0);
  label.refers = PpsTimeLabel::Refers::kNextPulse;
  label.quantization_error_valid = tp.quant_error_valid();
  label.quantization_error_s = label.quantization_error_valid ? tp.quant_error_ps * 1e-12 : 0.0;
  return label;
}

}  // namespace ldv::gnss
