// gnss_link: reads the GNSS receiver / RTK engine link (serial, TCP client or file; NMEA, RTKLIB
// solution stream or u-blox UBX) and publishes GNSS_SOLUTION and the PPS time labels on GNSS_PPS.
// Bad input is counted and skipped; nothing on the link can stop the service.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "common/logging.hpp"
#include "services/gnss_link/gnss_link_options.hpp"
#include "common/bus/gnss_messages.hpp"
#include "services/input/wait_readable.hpp"
#include "services/gnss_link/realtime_pacer.hpp"
#include "services/runtime/service_runtime.hpp"

namespace {
// STATUS_GNSS_LINK fault bits.
constexpr int32_t kFaultInputDown = 1 << 0;     // device not open / not connected
constexpr int32_t kFaultJumpRejected = 1 << 1;  // a position jump was rejected in the last 10 s
constexpr int32_t kFaultStale = 1 << 2;         // solutions stopped
constexpr int32_t kFaultBadInput = 1 << 3;      // checksum errors / truncated / malformed in the last 10 s
constexpr int32_t kFaultNoSolution = 1 << 4;  // messages arrive, but none gives a solution (e.g. GGA without a date)
constexpr double kFaultHold_s = 10.0;
// Epochs without a date before the link says why nothing is published (a receiver prints RMC/ZDA once a second).
constexpr std::uint64_t kUndatedEpochsBeforeWarning = 5;
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"gnss_link: GNSS receiver / RTK engine link (NMEA, RTKLIB stream, u-blox UBX from serial, TCP or "
               "file) -> GNSS_SOLUTION and GNSS_PPS"};
  std::string config_path, bus_url_override;
  app.add_option("-c,--config", config_path, "YAML configuration (deploy/config/gnss_link.yaml)");
  app.add_option("--bus-url", bus_url_override, "vehicle bus LCM URL (overrides the config)");
  CLI11_PARSE(app, argc, argv);
  ldv::init_logging();
  try {
    using namespace ldv::gnss;
    GnssLinkOptions o = load_gnss_link_options(config_path);
    if (!bus_url_override.empty()) o.bus_url = bus_url_override;

    ldv::ServiceRuntime rt("gnss_link", o.bus_url);
    auto source = ldv::io::make_byte_source(o.input);
    ldv::io::RealTimePacer pacer(o.input.type == "file" ? o.input.file_speed_factor : 0.0);
    JumpGate gate(o.jump_gate);
    int64_t solution_seq = 0, pps_seq = 0, previous_label_second = -1;
    double now_s = ldv::host_time_s();
    double last_solution_s = -1, last_jump_s = -1e9, last_bad_input_s = -1e9;
    uint64_t last_rejected = 0, undated_seen = 0;
    double last_undated_s = -1e9;
    bool undated_warned = false;

    auto on_solution = [&](const GnssSolution& s) {
      pacer.on_epoch(s.time.total_seconds(), now_s);
      const JumpVerdict v = gate.check(s);
      if (v == JumpVerdict::kJumpRejected || v == JumpVerdict::kTimeRejected) {
        last_jump_s = now_s;
        spdlog::warn("gnss_link: rejected solution at week {} sow {:.3f}: {}", s.time.week, s.time.sow_s,
                     v == JumpVerdict::kJumpRejected
                         ? fmt::format("{:.1f} m from the prediction (max {:.1f} m)", gate.last_deviation_m(),
                                       o.jump_gate.max_jump_m)
                         : std::string("not after the previous epoch"));
        return;
      }
      rt.bus().publish(o.solution_channel, to_message(s, solution_seq++, now_s));
      last_solution_s = now_s;
    };
    auto on_label = [&](const PpsTimeLabel& label) {
      rt.bus().publish(o.pps_channel, to_message(label, pps_seq++, now_s, previous_label_second));
      previous_label_second = label_total_second(label);
    };
    GnssStreamDecoder decoder(o.decoder, on_solution, on_label);

    spdlog::info("gnss_link: {} ({}) -> {} / {} on '{}'", source->describe(), link_protocol_name(o.decoder.protocol),
                 o.solution_channel, o.pps_channel, o.bus_url);
    // The device is opened before READY: the first heartbeat says whether it is (it said "input up" before the
    // open, and a writer that trusted it lost its first bytes to the open's flush).
    source->maintain(now_s);
    if (source->down()) rt.counters().fault_bits = kFaultInputDown;
    rt.ready();
    // Small reads when pacing a file keep the replay close to real time; otherwise take what is there.
    std::vector<uint8_t> buffer(o.input.type == "file" && o.input.file_speed_factor > 0 ? 512 : 16384);
    double last_bytes_s = now_s;
    bool epoch_flushed = true, end_flushed = false;
    while (rt.running()) {
      now_s = ldv::host_time_s();
      source->maintain(now_s);
      const double hold_s = pacer.hold_s(now_s);
      const int timeout_ms = hold_s > 0 ? std::clamp(static_cast<int>(hold_s * 1e3), 1, 50) : 50;
      const auto ready = ldv::io::wait_readable<1>({hold_s > 0 ? -1 : source->fd()}, timeout_ms);
      now_s = ldv::host_time_s();
      if (ready[0]) {
        const std::size_t n = source->read_some(buffer, now_s);
        if (n > 0) {
          decoder.feed(std::span<const uint8_t>(buffer.data(), n));
          last_bytes_s = now_s;
          epoch_flushed = false;
        }
      }
      if (!epoch_flushed && now_s - last_bytes_s > o.quiet_flush_s) {
        decoder.flush_epoch();
        epoch_flushed = true;
      }
      if (source->finished() && !end_flushed) {
        decoder.flush_end_of_input();
        end_flushed = epoch_flushed = true;
      }

      const GnssDecoderCounters c = decoder.counters();
      auto& counters = rt.counters();
      counters.received = static_cast<int64_t>(c.messages);
      counters.malformed = static_cast<int64_t>(c.rejected_total() + gate.counters().jumps_rejected +
                                                gate.counters().time_rejected);
      if (c.rejected_total() > last_rejected) last_bad_input_s = now_s;
      last_rejected = c.rejected_total();
      int32_t faults = 0;
      if (source->down()) faults |= kFaultInputDown;
      if (now_s - last_jump_s < kFaultHold_s) faults |= kFaultJumpRejected;
      if (last_solution_s > 0 && now_s - last_solution_s > o.stale_after_s && !source->finished()) faults |= kFaultStale;
      if (now_s - last_bad_input_s < kFaultHold_s) faults |= kFaultBadInput;
      // Messages but no solution: the port carries something, but not what a solution needs. Said once, held.
      const bool undated = c.epochs_without_date >= kUndatedEpochsBeforeWarning && c.epochs_without_date > undated_seen;
      if (undated) {
        undated_seen = c.epochs_without_date;
        last_undated_s = now_s;
        if (!undated_warned)
          spdlog::warn("gnss_link: {} NMEA epochs with a fix but no date (no RMC or ZDA on the port): the GPS week is "
                       "unknown, so no solution is published; enable RMC or ZDA on the receiver",
                       c.epochs_without_date);
        undated_warned = true;
      }
      if (now_s - last_undated_s < kFaultHold_s) faults |= kFaultNoSolution;
      counters.fault_bits = faults;
      rt.set_state(faults ? 2 : 1);
      rt.tick();
    }
    const GnssDecoderCounters c = decoder.counters();
    spdlog::info("gnss_link: stopping ({} via {}: messages {}, solutions {} published {}, labels {}, bad checksum {}, "
                 "truncated {}, malformed {}, implausible {}, jumps rejected {}, duplicates {}, garbage bytes {}, reconnects {})",
                 source->describe(), decoder.active(), c.messages, c.solutions, solution_seq, c.labels, c.bad_checksum,
                 c.truncated, c.malformed, c.implausible, gate.counters().jumps_rejected + gate.counters().time_rejected, c.duplicates,
                 c.garbage_bytes, source->counters().disconnects);
  } catch (const std::exception& e) {
    spdlog::error("gnss_link: {}", e.what());
    return 1;
  }
  return 0;
}
