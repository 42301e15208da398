#pragma once
// Byte streams for the service drivers, as the devices would send them:
//  - imu_device.bin: the time-stamp-unit protocol (common/formats/imu_device_frame.hpp): one IMU
//    sample frame per increment with the oscillator counter latched at the sample instant, and one
//    PPS latch frame per whole GPS second.
//  - gnss.nmea: per GNSS epoch GGA + GST + RMC (GGA with quality 0 and empty position during an
//    outage), and ZDA once per second labelling that second's PPS edge; in arrival order.
//  - a schedule (arrival GPS time, stream, byte offset, length) so a replay can pace both streams.
#include <cstdint>
#include <string>
#include <vector>

#include "common/formats/nav_types.hpp"

namespace ldv::sim {

// The time-stamp unit's free-running counter: counts(t) = phase + f (1 + ppm 1e-6) (t - t0) + jitter,
// modulo 2^32 (wraps every 2^32 / f seconds: 429 s at 10 MHz).
struct Oscillator {
  double nominal_hz = 10e6;
  double ppm = 25.0;
  double phase_counts = 0.0;     // counter value at t0
  double latch_jitter_s = 20e-9;  // std of the latch instant
};

struct ScheduleEntry {
  double t_sow_s;     // when the bytes leave the device
  int stream;         // 0 = imu_device.bin, 1 = gnss.nmea
  uint64_t offset, length;
};

struct DeviceStreams {
  std::vector<uint8_t> imu_bytes;
  std::string nmea_text;
  std::vector<ScheduleEntry> schedule;  // in time order
};

DeviceStreams make_device_streams(const std::vector<ImuIncrement>& imu, double t0_sow_s, int gps_week,
                                  const std::vector<GnssFix>& gnss, const std::vector<double>& gnss_latency_s,
                                  double gnss_rate_hz, double gnss_latency_mean_s, int leap_seconds,
                                  const Oscillator& osc, uint64_t seed, bool with_noise);

}  // namespace ldv::sim
