#include "services/fusion/fusion_input_gate.hpp"

#include "common/bus/message_conversions.hpp"
#include "common/time/gps_time.hpp"

namespace ldv {
namespace {
double continuous_s(int32_t week, double sow_s) { return week * kSecondsPerWeek + sow_s; }
}  // namespace

InputVerdict FusionInputGate::count(InputVerdict v) {
  switch (v) {
    case InputVerdict::kAccepted:
      break;
    case InputVerdict::kNotFinite:
      ++c_.not_finite;
      break;
    case InputVerdict::kNotGpsTime:
      ++c_.not_gps_time;
      break;
    case InputVerdict::kDeviceError:
      ++c_.device_error;
      break;
    case InputVerdict::kTooFarAhead:
      ++c_.too_far_ahead;
      break;
    case InputVerdict::kNotAfterLast:
      ++c_.not_after_last;
      break;
    case InputVerdict::kNotUsable:
      ++c_.not_usable;
      break;
    case InputVerdict::kJump:
      ++c_.jumps;
      break;
  }
  return v;
}

InputVerdict FusionInputGate::check(const ldv_lcm::imu_sample_t& m) {
  if (!is_valid(m)) return count(InputVerdict::kNotFinite);
  if (!o_.host_clock_imu && !has_gps_time(m)) return count(InputVerdict::kNotGpsTime);
  // The stamp of a device-error sample is good (only its increments are not): it moves the stream's time,
  // so the first good sample after the error is not mistaken for a jump.
  switch (imu_time_.check(continuous_s(m.gps_week, m.gps_sow_s))) {
    case MessageTimeGate::Verdict::kAccepted:
      return count((m.status & kImuStatusDeviceError) ? InputVerdict::kDeviceError : InputVerdict::kAccepted);
    case MessageTimeGate::Verdict::kTooFarAhead:
      return count(InputVerdict::kTooFarAhead);
    case MessageTimeGate::Verdict::kNotAfterLast:
      return count(InputVerdict::kNotAfterLast);
  }
  return InputVerdict::kAccepted;
}

bool FusionInputGate::ahead_of_imu(int32_t week, double sow_s) const {
  return imu_time_.has_accepted() && continuous_s(week, sow_s) > imu_time_.last_accepted_s() + o_.gnss_max_ahead_s;
}

InputVerdict FusionInputGate::check(const ldv_lcm::gnss_solution_t& m) {
  if (!is_valid(m)) return count(InputVerdict::kNotFinite);
  if (ahead_of_imu(m.gps_week, m.gps_sow_s)) return count(InputVerdict::kTooFarAhead);
  switch (jump_gate_.check(solution_from_message(m))) {
    case gnss::JumpVerdict::kJumpRejected:
      return count(InputVerdict::kJump);
    case gnss::JumpVerdict::kTimeRejected:
      return count(InputVerdict::kNotAfterLast);
    case gnss::JumpVerdict::kAccepted:
    case gnss::JumpVerdict::kRestarted:
      break;
  }
  return InputVerdict::kAccepted;
}

InputVerdict FusionInputGate::check(const ldv_lcm::wheel_speed_t& m) {
  if (!is_valid(m)) return count(InputVerdict::kNotFinite);
  if (!odometer_speed_from_message(m)) return count(InputVerdict::kNotUsable);
  if (ahead_of_imu(m.gps_week, m.gps_sow_s)) return count(InputVerdict::kTooFarAhead);
  return InputVerdict::kAccepted;
}

const char* describe(InputVerdict v) {
  switch (v) {
    case InputVerdict::kAccepted:
      return "accepted";
    case InputVerdict::kNotFinite:
      return "not finite or implausible";
    case InputVerdict::kNotGpsTime:
      return "not on GPS time";
    case InputVerdict::kDeviceError:
      return "device error flagged by imu_acq";
    case InputVerdict::kTooFarAhead:
      return "stamped too far ahead of the stream";
    case InputVerdict::kNotAfterLast:
      return "stamped at or before the last accepted sample";
    case InputVerdict::kNotUsable:
      return "wheel speed not valid or a wheel slipping";
    case InputVerdict::kJump:
      return "a GNSS position jump no vehicle makes between epochs (jump gate)";
  }
  return "?";
}

}  // namespace ldv
