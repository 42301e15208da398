#pragma once
// What fusion accepts from the bus, decided before anything reaches the estimator, so no single message
// can stop or corrupt navigation:
//  - IMU: finite numbers (is_valid), on GPS time (unless the IMU has only host-clock stamps), not flagged
//    as a device error by imu_acq (saturation, a failed self-test: the increments are not measurements;
//    the filter then bridges the gap from the next good sample, as for a lost one), and stamped forward
//    within imu_max_ahead_s of the last accepted sample (MessageTimeGate: a real jump is followed once the
//    new time line has held for a second).
//  - GNSS: finite and plausible (is_valid), not stamped more than gnss_max_ahead_s after the last
//    accepted IMU sample (a fix arrives after its epoch, never long before the IMU reaches it), and through
//    gnss_link's own jump gate (gnss_jump_gate.hpp: no position jump a vehicle cannot make between epochs, time
//    going forward): whatever publishes on the bus, fusion applies the checks a receiver's link applies.
//  - wheel speed: finite and plausible (is_valid), speeds flagged valid and no wheel slipping, and like a fix
//    not stamped more than gnss_max_ahead_s after the last accepted IMU sample.
// Every refusal is counted by reason.
#include <cstdint>
#include <ldv_lcm/gnss_solution_t.hpp>
#include <ldv_lcm/imu_sample_t.hpp>
#include <ldv_lcm/wheel_speed_t.hpp>

#include "common/formats/gnss_jump_gate.hpp"
#include "services/runtime/message_time_gate.hpp"

namespace ldv {

struct FusionInputOptions {
  bool host_clock_imu = false;    // accept IMU samples stamped from the host clock (no PPS)
  double imu_max_ahead_s = 1.0;   // largest step between accepted IMU stamps before confirmation is needed
  double gnss_max_ahead_s = 2.0;  // how far a fix may be stamped ahead of the last accepted IMU sample
  gnss::JumpGateOptions jump_gate;  // gnss_link's defaults
};

enum class InputVerdict {
  kAccepted,
  kNotFinite,     // is_valid failed: NaN, infinity, a non-positive variance or interval
  kNotGpsTime,    // IMU stamped from the host clock (skipped, not malformed: imu_acq not locked yet)
  kDeviceError,   // IMU status bit 1
  kTooFarAhead,   // stamped ahead of the stream's time (a bad stamp)
  kNotAfterLast,  // IMU stamped at or before the last accepted sample
  kNotUsable,     // wheel speed: not flagged valid, or a wheel flagged locked or slipping (expected, not malformed)
  kJump,          // GNSS: a position jump beyond the jump gate
};

struct FusionInputCounters {
  int64_t not_finite = 0, not_gps_time = 0, device_error = 0, too_far_ahead = 0, not_after_last = 0, not_usable = 0,
          jumps = 0;
  // Refused as bad input (the heartbeat's malformed count); host-clock samples are expected, not bad.
  int64_t malformed() const { return not_finite + device_error + too_far_ahead + not_after_last + jumps; }
};

class FusionInputGate {
 public:
  // IMU samples closer than 10 us are one sample twice (no IMU samples above 100 kHz; the KF-GINS reader's rule).
  static constexpr double kMinImuInterval_s = 1e-5;
  explicit FusionInputGate(FusionInputOptions o)
      : o_(o), imu_time_(o.imu_max_ahead_s, 3, 1.0, kMinImuInterval_s), jump_gate_(o.jump_gate) {}

  InputVerdict check(const ldv_lcm::imu_sample_t& m);
  InputVerdict check(const ldv_lcm::gnss_solution_t& m);
  InputVerdict check(const ldv_lcm::wheel_speed_t& m);
  const FusionInputCounters& counters() const { return c_; }
  // IMU time lines followed backwards (MessageTimeGate::jumps_back): the engine restarts on each.
  long imu_jumps_back() const { return imu_time_.jumps_back(); }

 private:
  InputVerdict count(InputVerdict v);
  bool ahead_of_imu(int32_t week, double sow_s) const;

  FusionInputOptions o_;
  MessageTimeGate imu_time_;
  gnss::JumpGate jump_gate_;
  FusionInputCounters c_;
};

const char* describe(InputVerdict v);

}  // namespace ldv
