// imu_acq: reads the IMU over a serial port (the time-stamp unit's framing or a MicroStrain
// 3DM-GX2), stamps every sample in GPS time from the PPS fit (DESIGN.md section 4) and publishes
// IMU, IMU_PPS and the 1 Hz IMU_TIMING statistics. Bad bytes are counted; nothing stops it.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <array>
#include <ldv_lcm/imu_sample_t.hpp>
#include <ldv_lcm/pps_event_t.hpp>
#include <memory>
#include <optional>
#include <vector>

#include "common/bus/gnss_messages.hpp"
#include "common/bus/message_conversions.hpp"
#include "common/logging.hpp"
#include "services/imu_acq/imu_acq_options.hpp"
#include "services/imu_acq/protocols/gx2_decoder.hpp"
#include "services/imu_acq/protocols/tsu_decoder.hpp"
#include "services/imu_acq/timing/kernel_pps_source.hpp"
#include "services/imu_acq/timing_report.hpp"
#include "services/input/wait_readable.hpp"
#include "services/runtime/service_runtime.hpp"

namespace {
using namespace ldv;
using namespace ldv::imu;

// STATUS_IMU_ACQ fault bits.
constexpr int32_t kFaultInputDown = 1 << 0;   // serial port not open
constexpr int32_t kFaultUnlocked = 1 << 1;    // stamps extrapolated (no PPS fit)
constexpr int32_t kFaultNoLabels = 1 << 2;    // no GNSS_PPS label for 3 s (device PPS only)
constexpr int32_t kFaultBadFrames = 1 << 3;   // checksum errors in the last 10 s
constexpr int32_t kFaultNoSamples = 1 << 4;   // no sample for 1 s
constexpr int32_t kFaultPpsDevice = 1 << 5;   // kernel PPS device unusable

// IMU status bits (imu_sample_t.status).
constexpr int32_t kStatusExtrapolated = 1 << 0;  // from the host clock: not on GPS time (common/bus)
constexpr int32_t kStatusDeviceError = ldv::kImuStatusDeviceError;
constexpr int32_t kStatusHoldover = 1 << 2;       // from a previous or saved PPS fit, no live PPS behind it
// IMU_PPS flags (pps_event_t.flags).
constexpr int32_t kPpsMissingPrevious = 1 << 0, kPpsLate = 1 << 1, kPpsRejected = 1 << 2;

std::unique_ptr<ImuDeviceDecoder> make_decoder(const ImuAcqOptions& o) {
  if (o.protocol == DeviceProtocol::kGx2) return std::make_unique<Gx2Decoder>(o.gx2_timer_hz, 1.0 / o.sample_rate_hz);
  return std::make_unique<TsuDecoder>(o.tsu_counter_hz);
}

int32_t pps_flags(const timing::PpsEdgeResult& r) {
  using V = timing::PpsEdgeVerdict;
  int32_t f = r.missing_before > 0 ? kPpsMissingPrevious : 0;
  if (r.verdict == V::kLate) f |= kPpsLate;
  if (r.verdict == V::kLate || r.verdict == V::kSpurious || r.verdict == V::kUnlabelled ||
      r.verdict == V::kAcceptedWrongLabel)
    f |= kPpsRejected;
  return f;
}
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"imu_acq: IMU serial driver (time-stamp unit framing, MicroStrain 3DM-GX2) with PPS time-stamping "
               "in GPS time -> IMU, IMU_PPS, IMU_TIMING"};
  std::string config_path, bus_url_override;
  app.add_option("-c,--config", config_path, "YAML configuration (deploy/config/imu_acq.yaml)");
  app.add_option("--bus-url", bus_url_override, "vehicle bus LCM URL (overrides the config)");
  CLI11_PARSE(app, argc, argv);
  init_logging();
  try {
    ImuAcqOptions o = load_imu_acq_options(config_path);
    if (!bus_url_override.empty()) o.bus_url = bus_url_override;
    if (o.calibration)
      spdlog::info("imu_acq: calibration {} applied in the device frame, then the mounting rotation ({})",
                   o.calibration_file, o.calibration->description.empty() ? "no description" : o.calibration->description);

    ServiceRuntime rt("imu_acq", o.bus_url);
    auto source = io::make_byte_source(o.input);
    auto decoder = make_decoder(o);
    const bool kernel_pps = o.pps_source == PpsSource::kKernel;
    // With the kernel PPS the "counter" is the host clock in nanoseconds, for samples and edges.
    o.stamper.fit.counter_bits = kernel_pps ? 64 : decoder->counter_bits();
    o.stamper.fit.nominal_counter_hz = kernel_pps ? 1e9 : decoder->nominal_counter_hz();

    int64_t imu_seq = 0, pps_seq = 0, timing_seq = 0;
    double now_s = host_time_s();
    double last_label_s = -1e9, last_sample_s = -1e9, last_bad_frame_s = -1e9;
    std::uint64_t skipped_bytes_seen = 0;  // undecodable bytes already counted into the bad-frames fault
    bool undecodable_said = false;
    ImuTimeStamper stamper(o.stamper, [&](const JudgedEdge& e) {
      ldv_lcm::pps_event_t m{};
      m.seq = pps_seq++;
      if (e.gps_second) {
        m.gps_week = static_cast<int32_t>(*e.gps_second / 604800);
        m.gps_sow_s = static_cast<double>(*e.gps_second % 604800);
      }
      m.counter_raw = e.counter;
      m.host_time_s = e.host_time_s;
      m.flags = pps_flags(e.result);
      rt.bus().publish(o.pps_channel, m);
    });
    if (!o.fit_state_file.empty()) {
      if (const auto saved = load_fit_state(o.fit_state_file, host_time_s(), o.fit_state_max_age_s)) {
        stamper.seed(*saved);
        spdlog::info("imu_acq: PPS fit saved {:.1f} s ago in {}: stamps stay on GPS time until the fit re-locks",
                     host_time_s() - saved->saved_host_time_s, o.fit_state_file);
      }
    }
    double next_fit_save_s = now_s + 1.0;
    TimingReport report(1.0 / o.sample_rate_hz, o.hist_bin_s);
    std::optional<GpsTime> previous_stamp;
    uint64_t lost_seen = 0;

    decoder->on_sample([&](const DeviceSample& d) {
      last_sample_s = now_s;
      const uint64_t counter = kernel_pps ? static_cast<uint64_t>(now_s * 1e9) : d.counter;
      const Stamp st = stamper.stamp(counter, now_s);
      const uint64_t lost = decoder->counters().lost_samples;
      if (lost != lost_seen || st.extrapolated) report.break_chain();
      lost_seen = lost;
      if (!st.extrapolated) report.add_locked_stamp(st.time);

      ldv_lcm::imu_sample_t m{};
      m.seq = imu_seq++;
      m.gps_week = st.time.week;
      m.gps_sow_s = st.time.sow_s;
      m.counter_raw = st.counter;
      m.host_time_s = now_s;
      m.dt_s = previous_stamp ? (st.time.week - previous_stamp->week) * kSecondsPerWeek + (st.time.sow_s - previous_stamp->sow_s)
                              : 1.0 / o.sample_rate_hz;
      previous_stamp = st.time;
      Vec3 dtheta = d.dtheta_b_rad, dvel = d.dvel_b_mps;
      o.correction.apply(dtheta, dvel, m.dt_s);
      for (int i = 0; i < 3; ++i) {
        m.dtheta_b_rad[i] = dtheta[i];
        m.dvel_b_mps[i] = dvel[i];
      }
      m.status = (st.extrapolated && !st.holdover ? kStatusExtrapolated : 0) | (st.holdover ? kStatusHoldover : 0) |
                 (d.device_error ? kStatusDeviceError : 0);
      rt.bus().publish(o.imu_channel, m);
    });
    decoder->on_pps([&](const DevicePpsLatch& p) {
      if (o.pps_source == PpsSource::kDevice) stamper.on_pps_latch(p.counter, now_s);
    });

    SequenceTracker label_seq;
    rt.bus().subscribe<ldv_lcm::pps_event_t>(o.label_channel, [&](const ldv_lcm::pps_event_t& m, const std::string&) {
      rt.counters().dropped += label_seq.observe(m.seq);
      gnss::PpsTimeLabel label = gnss::label_from_message(m);
      if (o.label_side == LabelSide::kLastPulse) label.refers = gnss::PpsTimeLabel::Refers::kLastPulse;
      if (o.label_side == LabelSide::kNextPulse) label.refers = gnss::PpsTimeLabel::Refers::kNextPulse;
      last_label_s = host_time_s();
      stamper.on_label(label, last_label_s);
    }, 100);

    bool kernel_failed = false;
    // KernelPpsSource moves but does not assign: initialise the optional in place.
    std::optional<timing::KernelPpsSource> kernel_source = [&]() -> std::optional<timing::KernelPpsSource> {
      if (!kernel_pps) return std::nullopt;
      std::string error;
      auto s = timing::KernelPpsSource::open(o.kernel_pps_device, error);
      if (!s) {
        kernel_failed = true;
        spdlog::error("imu_acq: kernel PPS {}: {} (stamps stay extrapolated)", o.kernel_pps_device, error);
      }
      return s;
    }();
    auto* serial = dynamic_cast<io::SerialPort*>(source.get());
    uint64_t opens_seen = 0;

    spdlog::info("imu_acq: {} ({}, PPS from {}) -> {} / {} / {} on '{}'", source->describe(),
                 o.protocol == DeviceProtocol::kGx2 ? "3DM-GX2" : "time-stamp unit",
                 kernel_pps ? o.kernel_pps_device : (o.pps_source == PpsSource::kDevice ? "device latches" : "nowhere"),
                 o.imu_channel, o.pps_channel, o.timing_channel, o.bus_url);
    // The device is opened before READY: the first heartbeat says whether it is (it said "input up" before the
    // open, and a writer that trusted it lost its first bytes to the open's flush).
    source->maintain(now_s);
    if (source->down()) rt.counters().fault_bits = kFaultInputDown;
    rt.ready();
    std::vector<uint8_t> buffer(8192);
    double next_report_s = now_s + 1.0;
    while (rt.running()) {
      now_s = host_time_s();
      source->maintain(now_s);
      if (serial && source->counters().opens != opens_seen) {
        opens_seen = source->counters().opens;
        // A 3DM-GX2 forgets continuous mode on power cycles: ask again on every (re)open.
        if (o.protocol == DeviceProtocol::kGx2 && o.gx2_continuous_record != 0)
          serial->write_all(gx2::start_continuous_command(static_cast<uint8_t>(o.gx2_continuous_record)));
      }
      const auto ready = io::wait_readable<2>({rt.bus().fd(), source->fd()}, 20);
      now_s = host_time_s();
      if (ready[0]) rt.bus().handle(0);
      if (ready[1]) {
        const std::size_t n = source->read_some(buffer, now_s);
        if (n > 0) decoder->feed(std::span<const uint8_t>(buffer.data(), n));
      }
      if (kernel_source) {
        std::string error;
        while (const auto ev = kernel_source->fetch(0.0, error)) stamper.on_pps_latch(static_cast<uint64_t>(ev->assert_time_ns), now_s);
      }
      stamper.poll(now_s);

      const DecoderCounters& dc = decoder->counters();
      auto& counters = rt.counters();
      if (static_cast<int64_t>(dc.bad_checksum) > counters.malformed) last_bad_frame_s = now_s;
      // Bytes no frame of the configured protocol holds are not dropped in silence (issue 46: a stream of them
      // ended as "frames 0, bad checksum 0"): they raise the bad-frames fault and are said once.
      // (The first bytes may be the tail of a frame the device sent before we listened: a frame's length is spared.)
      constexpr std::uint64_t kStartSlackBytes = 256;
      if (dc.skipped_bytes > std::max(skipped_bytes_seen, kStartSlackBytes)) {
        last_bad_frame_s = now_s;
        if (!undecodable_said && dc.skipped_bytes >= 1024) {
          spdlog::warn(
              "imu_acq: {} bytes received that are no {} frame ({} frames decoded): is protocol right, "
              "or the line's speed?",
              dc.skipped_bytes, o.protocol == DeviceProtocol::kGx2 ? "3DM-GX2" : "time-stamp unit", dc.frames);
          undecodable_said = true;
        }
        skipped_bytes_seen = dc.skipped_bytes;
      }
      counters.received = static_cast<int64_t>(dc.frames);
      counters.malformed = static_cast<int64_t>(dc.bad_checksum);
      counters.dropped = static_cast<int64_t>(dc.lost_samples + label_seq.lost());
      int32_t faults = 0;
      if (source->down()) faults |= kFaultInputDown;
      if (!stamper.fit().locked()) faults |= kFaultUnlocked;
      if (o.pps_source != PpsSource::kNone && now_s - last_label_s > 3.0) faults |= kFaultNoLabels;
      if (now_s - last_bad_frame_s < 10.0) faults |= kFaultBadFrames;
      if (now_s - last_sample_s > 1.0) faults |= kFaultNoSamples;
      if (kernel_failed) faults |= kFaultPpsDevice;
      counters.fault_bits = faults;
      rt.set_state(faults ? 2 : 1);
      if (!o.fit_state_file.empty() && now_s >= next_fit_save_s) {
        if (const auto fs = stamper.fit_state(now_s)) save_fit_state(o.fit_state_file, *fs);
        next_fit_save_s = now_s + 2.0;
      }
      if (now_s >= next_report_s) {
        rt.bus().publish(o.timing_channel, report.message(timing_seq++, now_s, stamper.fit(), 0));
        next_report_s += 1.0;
        if (next_report_s < now_s) next_report_s = now_s + 1.0;
      }
      rt.tick();
    }
    const auto& fc = stamper.fit().counters();
    spdlog::info(
        "imu_acq: stopping (frames {}, samples published {}, bad checksum {}, undecodable bytes {}, lost samples "
        "{}, PPS edges {} accepted {} missing {} late {}, interval {:.9f} s +- {:.3f} us, drift {:.3f} ppm)",
        decoder->counters().frames, imu_seq, decoder->counters().bad_checksum, decoder->counters().skipped_bytes,
        decoder->counters().lost_samples, fc.edges, fc.accepted, fc.missing, fc.late, report.mean_s(),
        report.std_s() * 1e6, stamper.fit().frequency_offset_ppm());
  } catch (const std::exception& e) {
    spdlog::error("imu_acq: {}", e.what());
    return 1;
  }
  return 0;
}
