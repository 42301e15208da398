#pragma once
// Named status bits of the filter (published by the fusion service in FUSION_STATUS).
#include <cstdint>
#include <string>

namespace ldv::est {

enum StatusBit : std::uint32_t {
  kStatusInitialized = 1u << 0,     // has a navigation state
  kStatusGnssRejected = 1u << 1,    // the last GNSS measurement failed the innovation gate
  kStatusGateResync = 1u << 2,      // accepted after too many consecutive gate rejections
  kStatusCovarianceReset = 1u << 3, // covariance was not finite / not positive definite: reset (event)
  kStatusStateReset = 1u << 4,      // navigation state became non-finite: restored (event)
  kStatusZuptActive = 1u << 5,      // the static detector fires
  kStatusImuRejected = 1u << 6,     // an IMU sample was non-finite or had a bad interval: skipped (event)
  kStatusImuGap = 1u << 7,          // an IMU interval longer than 5 nominal intervals (event)
  kStatusLateDropped = 1u << 8,     // a measurement older than the history horizon was dropped (event)
  kStatusGnssOutage = 1u << 9,      // no accepted GNSS for more than 2 s
  kStatusMeasurementRejected = 1u << 10,  // a non-finite measurement was dropped (event)
};

// Counts of the event bits since the start (status bits show only the latest state).
struct FaultCounters {
  long covariance_resets = 0, state_resets = 0, imu_rejected = 0, imu_gaps = 0, late_dropped = 0, gate_rejections = 0,
       gate_resyncs = 0, measurements_rejected = 0;
  long downweighted = 0;     // beyond the gate, kept by the robust update with its noise inflated
  long fixes_retracted = 0;  // suspect fixes undone: the next fix fitted only without them (retract_suspect_fix)
  long zupts_applied = 0, zupts_skipped_moving = 0;  // the latter: a stop's ZUPT that disagreed (the start)
};

std::string describe_status(std::uint32_t bits);

}  // namespace ldv::est
