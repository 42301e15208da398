// fusion: the estimator as a service. Subscribes IMU and GNSS_SOLUTION (and WHEEL_SPEED with the odometer
// aid), runs FusionEngine (the estimator's NavSession, as `ldv nav` does), publishes NAV at the IMU rate,
// NAV_INNOVATION at the GNSS rate and its heartbeat; saves a warm-start state once a second.
#include <CLI/CLI.hpp>
#include <chrono>
#include <filesystem>
#include <ldv_lcm/nav_innovation_t.hpp>
#include <ldv_lcm/nav_state_t.hpp>
#include <thread>

#include "common/bus/message_conversions.hpp"
#include "common/config/config_section.hpp"
#include "common/formats/kfgins_config.hpp"
#include "common/logging.hpp"
#include "estimator/run/run_navigation.hpp"
#include "services/fusion/fusion_engine.hpp"
#include "services/fusion/fusion_input_gate.hpp"
#include "services/fusion/nav_message.hpp"
#include "services/runtime/service_runtime.hpp"

namespace {
struct FusionConfig {
  std::string bus_url;
  std::string kfgins_config;  // KF-GINS YAML: imunoise, antlever, ldv: model/add/drop (paths unused)
  double align_wait_s = 1.0;
  double history_s = 3.0;     // how late a GNSS solution may arrive and still be applied at its epoch
  std::string state_file;     // warm-start state ("" = none)
  double warm_start_max_age_s = 30.0;
  // IMU samples stamped from the host clock (imu_acq status bit 0) are skipped: they are not on GPS time.
  // An IMU without PPS (imu_acq pps.source: none) has only those: then set this.
  bool host_clock_imu = false;
  double imu_max_ahead_s = 1.0;   // FusionInputOptions
  double gnss_max_ahead_s = 2.0;
};

FusionConfig load_config(const std::string& path) {
  using ldv::config::Range;
  FusionConfig c;
  if (path.empty()) return c;
  ldv::config::ConfigSection y = ldv::config::ConfigSection::load(path);
  c.bus_url = y.text("bus_url", c.bus_url);
  c.kfgins_config = y.text("kfgins_config", c.kfgins_config);
  c.align_wait_s = y.number("align_wait_s", c.align_wait_s, Range::at_least(0.0).up_to(3600.0));
  c.history_s = y.number("history_s", c.history_s, Range::at_least(0.0).up_to(60.0));
  c.state_file = y.text("state_file", c.state_file);
  c.warm_start_max_age_s = y.number("warm_start_max_age_s", c.warm_start_max_age_s, Range::above(0.0));
  c.host_clock_imu = y.flag("host_clock_imu", c.host_clock_imu);
  c.imu_max_ahead_s = y.number("imu_max_ahead_s", c.imu_max_ahead_s, Range::above(0.0).up_to(60.0));
  c.gnss_max_ahead_s = y.number("gnss_max_ahead_s", c.gnss_max_ahead_s, Range::above(0.0).up_to(60.0));
  y.refuse_unknown();
  return c;
}
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"fusion: GPS/INS error-state EKF service (IMU + GNSS_SOLUTION -> NAV, NAV_INNOVATION)"};
  std::string config_path, bus_url_override, kfgins_override;
  app.add_option("-c,--config", config_path, "YAML configuration (deploy/config/fusion.yaml)");
  app.add_option("--bus-url", bus_url_override, "LCM URL (overrides the config)");
  app.add_option("--kfgins-config", kfgins_override, "KF-GINS configuration with the IMU noise model (overrides the config)");
  CLI11_PARSE(app, argc, argv);
  ldv::init_logging();
  try {
    FusionConfig cfg = load_config(config_path);
    if (!bus_url_override.empty()) cfg.bus_url = bus_url_override;
    if (!kfgins_override.empty()) cfg.kfgins_config = kfgins_override;
    if (cfg.kfgins_config.empty()) throw std::runtime_error("no kfgins_config given (the IMU noise model)");
    const ldv::KfGinsConfig kcfg = ldv::load_kfgins_config(cfg.kfgins_config);
    ldv::est::FilterOptions fo = ldv::est::options_from_kfgins(kcfg);
    fo.history_s = cfg.history_s;
    // The session the KF-GINS configuration describes, as `ldv nav` runs it (given start, start/end time,
    // heading hypotheses, aids), with this service's alignment wait.
    ldv::est::SessionOptions so = ldv::live_session_options(kcfg, fo);
    so.align_wait_s = cfg.align_wait_s;
    ldv::FusionEngine engine(so);
    if (!cfg.state_file.empty()) {
      std::string refused_why;
      if (auto w = ldv::load_warm_state(cfg.state_file, ldv::host_time_s(), cfg.warm_start_max_age_s, &refused_why)) {
        engine.set_warm_start(*w);
        spdlog::info("fusion: warm start available from {} (saved {:.1f} s ago)", cfg.state_file,
                     ldv::host_time_s() - w->saved_host_time_s);
      } else if (std::error_code ec; std::filesystem::exists(cfg.state_file, ec)) {
        spdlog::warn("fusion: warm-state file {} not used ({}): aligning instead", cfg.state_file, refused_why);
      }
    }

    ldv::ServiceRuntime rt("fusion", cfg.bus_url);
    ldv::SequenceTracker imu_seq, gnss_seq, wheel_seq;
    int64_t nav_seq = 0, innovation_seq = 0;
    double last_innovation_t = -1e300, next_save_s = 0;
    std::vector<ldv::FusionOutput> outputs;
    bool announced = false;
    size_t latency_decisions_logged = 0;

    auto publish = [&](std::vector<ldv::FusionOutput>& outs) {
      for (size_t i = 0; i < outs.size(); ++i) {
        // The backlog released at alignment can be hundreds of NAV at once: pace it, so subscribers
        // with LCM's default 30-message queue (lcm-logger 1.3.1) keep up.
        if (i > 0 && i % 16 == 0) std::this_thread::sleep_for(std::chrono::milliseconds(2));
        rt.bus().publish("NAV", ldv::nav_message(outs[i], nav_seq++));
      }
      outs.clear();
      for (const auto& r : engine.filter().take_innovations()) {
        if (r.t_s <= last_innovation_t && r.sensor == ldv::est::sensors::kGnssPosition) continue;
        if (r.replayed && r.t_s <= last_innovation_t) continue;  // already published before a rewind
        rt.bus().publish("NAV_INNOVATION", ldv::innovation_message(r, engine.week_time(r.t_s), innovation_seq++));
        // A GNSS solution the innovation gate refused is rejected input (service_status_t.malformed).
        if (!r.used()) ++rt.counters().malformed;  // rejected, or kept by the robust update with a trace of weight
        last_innovation_t = std::max(last_innovation_t, r.t_s);
      }
      if (engine.navigating() && !announced) {
        spdlog::info("fusion: navigating ({})", engine.initialisation());
        announced = true;
      }
      if (const ldv::est::ImuLatencyWindow* w = engine.session().imu_latency_window();
          w && w->decisions().size() > latency_decisions_logged) {
        const ldv::est::ImuLatencyDecision& d = w->decisions().back();
        spdlog::info("fusion: IMU stamps late by {:.1f} +- {:.1f} ms (found from {} turning GNSS intervals up to "
                     "{:.3f} s; taken out of the stamps from {:.3f} s on)",
                     1e3 * d.lag_s, 1e3 * d.sigma_s, d.turning_intervals, d.window_end_s, d.from_imu_t_s);
        latency_decisions_logged = w->decisions().size();
      }
    };

    ldv::FusionInputOptions gate_options;
    gate_options.host_clock_imu = cfg.host_clock_imu;
    gate_options.imu_max_ahead_s = cfg.imu_max_ahead_s;
    gate_options.gnss_max_ahead_s = cfg.gnss_max_ahead_s;
    ldv::FusionInputGate gate(gate_options);
    long jumps_back_seen = 0;
    double last_refusal_s = -1e300;
    // Refused input is counted (heartbeat: malformed) and logged once per reason change, never fatal.
    ldv::InputVerdict last_logged = ldv::InputVerdict::kAccepted;
    auto refused = [&](ldv::InputVerdict v, const char* channel, int week, double sow_s) {
      if (v == ldv::InputVerdict::kAccepted) return false;
      if (v == ldv::InputVerdict::kNotGpsTime) return true;  // imu_acq not on GPS time yet (before its PPS fit)
      ++rt.counters().malformed;
      last_refusal_s = ldv::host_time_s();
      if (v != last_logged) spdlog::warn("fusion: {} message (week {}, {:.3f} s) refused: {}", channel, week, sow_s, ldv::describe(v));
      last_logged = v;
      return true;
    };

    rt.bus().subscribe<ldv_lcm::imu_sample_t>("IMU", [&](const ldv_lcm::imu_sample_t& m, const std::string&) {
      ++rt.counters().received;
      rt.counters().dropped += imu_seq.observe(m.seq);
      if (refused(gate.check(m), "IMU", m.gps_week, m.gps_sow_s)) return;
      if (gate.imu_jumps_back() > jumps_back_seen) {  // the whole IMU stream went back in time: start again
        jumps_back_seen = gate.imu_jumps_back();
        spdlog::warn("fusion: the IMU stream went back in time to week {} {:.3f} s and held there: navigation "
                     "restarts on it (warm from the last state)", m.gps_week, m.gps_sow_s);
        engine.restart_on_new_time_line(ldv::host_time_s());
        last_innovation_t = -1e300;
        announced = false;
      }
      engine.on_imu(ldv::imu_from_message(m), m.gps_week, ldv::host_time_s(), outputs);
      publish(outputs);
    }, 20000);
    rt.bus().subscribe<ldv_lcm::gnss_solution_t>("GNSS_SOLUTION", [&](const ldv_lcm::gnss_solution_t& m, const std::string&) {
      ++rt.counters().received;
      rt.counters().dropped += gnss_seq.observe(m.seq);
      if (refused(gate.check(m), "GNSS_SOLUTION", m.gps_week, m.gps_sow_s)) return;
      engine.on_gnss(ldv::gnss_from_message(m), m.gps_week, ldv::host_time_s());
    }, 1000);
    if (engine.wants_odometer())
      rt.bus().subscribe<ldv_lcm::wheel_speed_t>(
          "WHEEL_SPEED",
          [&](const ldv_lcm::wheel_speed_t& m, const std::string&) {
            ++rt.counters().received;
            rt.counters().dropped += wheel_seq.observe(m.seq);
            const ldv::InputVerdict v = gate.check(m);
            if (v == ldv::InputVerdict::kNotUsable) return;  // a slipping wheel: expected, not bad input
            if (refused(v, "WHEEL_SPEED", m.gps_week, m.gps_sow_s)) return;
            engine.on_wheel_speed(m, ldv::host_time_s(), outputs);
            publish(outputs);
          },
          1000);

    rt.ready();
    while (rt.running()) {
      rt.bus().handle(20);
      engine.on_idle(ldv::host_time_s(), outputs);
      publish(outputs);
      rt.counters().fault_bits = static_cast<int32_t>(engine.filter().status());
      // Degraded while input was refused in the last 10 s: running, but not on every message.
      const bool refusing = ldv::host_time_s() - last_refusal_s < 10.0;
      rt.set_state(!engine.navigating() ? 0 : refusing ? 2 : 1);
      rt.tick();
      if (!cfg.state_file.empty() && engine.navigating() && ldv::host_time_s() >= next_save_s) {
        ldv::save_warm_state(cfg.state_file, engine.warm_state(ldv::host_time_s()));
        next_save_s = ldv::host_time_s() + 1.0;
      }
    }
    spdlog::info("fusion: stopping (received {}, dropped {}, malformed {}, status {})", rt.counters().received,
                 rt.counters().dropped, rt.counters().malformed, ldv::est::describe_status(engine.filter().status()));
  } catch (const std::exception& e) {
    spdlog::error("fusion: {}", e.what());
    return 1;
  }
  return 0;
}
