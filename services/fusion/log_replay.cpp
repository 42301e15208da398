#include "services/fusion/log_replay.hpp"

#include "common/bus/decode_message.hpp"
#include "common/bus/lcm_log_reader.hpp"
#include "common/bus/message_conversions.hpp"
#include "common/io/input_error.hpp"
#include "services/fusion/fusion_input_gate.hpp"

namespace ldv {
namespace {
const std::string kWheelSpeedChannel = "WHEEL_SPEED";
}  // namespace

LogReplaySummary replay_fusion_log(const std::string& log_path, FusionEngine& engine,
                                   const std::function<void(const FusionOutput&)>& on_output,
                                   const std::string& imu_channel, const std::string& gnss_channel, bool host_clock_imu) {
  LcmLogReader log(log_path);
  LogReplaySummary sum;
  std::vector<FusionOutput> outs;
  FusionInputOptions gate_options;  // the live service's defaults
  gate_options.host_clock_imu = host_clock_imu;
  FusionInputGate gate(gate_options);
  long jumps_back_seen = 0;
  LcmLogEvent ev;
  while (log.next(ev)) {
    const double arrival_s = ev.timestamp_us * 1e-6;  // logger receive time [us] -> s
    if (ev.channel == imu_channel) {
      ldv_lcm::imu_sample_t m;
      if (!decode_message(ev.data, m)) {
        ++sum.malformed;
        continue;
      }
      const InputVerdict v = gate.check(m);  // as the live service
      if (v != InputVerdict::kAccepted && v != InputVerdict::kNotGpsTime) {
        ++sum.malformed;
        continue;
      }
      ++sum.imu_messages;
      if (v == InputVerdict::kNotGpsTime) continue;
      if (gate.imu_jumps_back() > jumps_back_seen) {  // as the live service: the stream went back, start again
        jumps_back_seen = gate.imu_jumps_back();
        engine.restart_on_new_time_line(arrival_s);
      }
      engine.on_imu(imu_from_message(m), m.gps_week, arrival_s, outs);
    } else if (ev.channel == gnss_channel) {
      ldv_lcm::gnss_solution_t m;
      if (!decode_message(ev.data, m) || gate.check(m) != InputVerdict::kAccepted) {
        ++sum.malformed;
        continue;
      }
      ++sum.gnss_messages;
      engine.on_gnss(gnss_from_message(m), m.gps_week, arrival_s);
    } else if (ev.channel == kWheelSpeedChannel && engine.wants_odometer()) {
      ldv_lcm::wheel_speed_t m;
      const bool decoded = decode_message(ev.data, m);
      const InputVerdict v = decoded ? gate.check(m) : InputVerdict::kNotFinite;
      if (v == InputVerdict::kNotUsable) continue;  // flagged by the sensor itself: expected, not malformed
      if (v != InputVerdict::kAccepted) {
        ++sum.malformed;
        continue;
      }
      ++sum.wheel_messages;
      engine.on_wheel_speed(m, arrival_s, outs);
    } else {
      ++sum.other_messages;
      engine.on_idle(arrival_s, outs);
    }
    for (const auto& o : outs) on_output(o);
    outs.clear();
  }
  sum.corrupt_log_events = log.corrupt_events() + log.truncated_events();
  engine.on_end(outs);
  for (const auto& o : outs) on_output(o);
  sum.initialisation = engine.initialisation();
  return sum;
}

}  // namespace ldv
