// `ldv nav`: the GPS/INS filter over files (DESIGN.md section 2; estimator/README.md).
//   ldv nav --kfgins-config FILE.yaml [--model NAME] [--add EFFECT]... [--drop EFFECT]... [--out FILE.nav]
//   ldv nav --imu imu.txt --gnss gnss.txt [--lever x y z] ...
//   ldv nav --imu-csv imu.csv [--imu-tag imu.csv.tag] --pos rtk.pos [--pos-height-offset N] ...   (the walk;
//            or a config whose imupath ends in .csv and gnsspath in .pos: tests/estimator/data/walk_0827_mems.yaml)
//   ldv nav --lcm-log FILE.lcm --kfgins-config FILE.yaml   (replays the live fusion service's engine: the same
//            NavSession as over files, estimator/run/nav_session.hpp)
//   ldv smooth ... (= ldv nav --smooth ...): the forward run, then the Rauch-Tung-Striebel backward pass
//            (estimator/smooth); the smoothed solution in --out, the forward one in FILE_forward.nav.
// Inputs: IMU from KF-GINS imu.txt (--imu or the config) or a time-tagged CSV (--imu-csv); GNSS from KF-GINS
// gnss.txt (--gnss or the config) or an RTKLIB .pos (--pos); or both from an LCM log (--lcm-log). IMU files are
// corrected by an `ldv calib static` calibration (--calibration or ldv.calibration; toolbox/assess/nav_inputs.hpp).
// Outputs: FILE.nav (KF-GINS layout, one line per IMU sample), FILE_std.txt, FILE_innovations.txt
// (tools/ldv/nav_outputs.hpp); smoothed: also FILE_separation.txt, and FILE_forward{.nav,_std.txt,_innovations.txt}.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>

#include "common/formats/kfgins_config.hpp"
#include "common/formats/kfgins_files.hpp"
#include "common/io/input_error.hpp"
#include "common/io/output_file.hpp"
#include "common/io/text_table.hpp"
#include "common/logging.hpp"
#include "estimator/run/alignment_options_from.hpp"
#include "estimator/run/run_navigation.hpp"
#include "services/fusion/log_replay.hpp"
#include "toolbox/assess/nav_inputs.hpp"
#include "tools/ldv/cli_checks.hpp"
#include "tools/ldv/command_registry.hpp"
#include "tools/ldv/nav_input_options.hpp"
#include "tools/ldv/nav_outputs.hpp"

namespace {
namespace fs = std::filesystem;
using namespace ldv;

struct NavArgs {
  assess::NavInputArgs in;  // the file inputs, shared with ldv outage / diagnose (nav_input_options.hpp)
  std::string lcm_log, out;
  std::string write_inputs;  // a folder: the inputs as the filter takes them, as KF-GINS files
  int week = -1;
  double std_rate_hz = 10.0;
  double align_speed_mps = -1.0;  // <= 0: the config's ldv.align_speed_mps
  int align_hypotheses = 0;       // 0: the config's ldv.align_hypotheses
  double history_s = 3.0;
  double align_wait_s = 1.0;
  bool quiet = false, print_options = false, host_clock_imu = false;
  bool smooth = false;
};

int week_from_config(const KfGinsConfig& cfg) {
  if (!cfg.ldv.IsDefined() || cfg.ldv.IsNull() || !cfg.ldv["week"]) return -1;
  try {
    return cfg.ldv["week"].as<int>();
  } catch (const YAML::Exception&) {
    throw InputError(cfg.config_path, cfg.ldv["week"].Mark().line + 1, "key 'ldv.week': expected an integer GPS week");
  }
}

// The .nav path (--out, else the configuration's outputpath), its folder made if it is not there yet (`ldv smooth`
// writes FILE_forward.nav and the other outputs beside it).
std::string default_nav_path(const NavArgs& a, const KfGinsConfig& cfg) {
  const fs::path nav = !a.out.empty()
                           ? fs::path(a.out)
                           : fs::path(cfg.output_path.empty() ? "." : cfg.output_path) / "KF_GINS_Navresult.nav";
  const std::string dir = nav.parent_path().empty() ? "." : nav.parent_path().string();
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw InputError(dir, 0, "cannot create the output directory: " + ec.message());
  return nav.string();
}

// standstill_s: the standstill the IMU noise as installed was measured over (0: none).
void print_summary(const char* what, long imu_samples, double t0, double t1, long fixes, const std::string& init,
                   const est::NavFilter& f, double elapsed, const std::string& nav_path, double standstill_s) {
  const auto& ft = f.faults();
  std::fprintf(stderr,
               "ldv nav: %s: %ld IMU samples from %.3f to %.3f s, %ld GNSS fixes; initial state: %s\n"
               "  gate rejections %ld (resyncs %ld, edge fixes retracted %ld), late measurements dropped %ld (older "
               "than the IMU history), covariance resets %ld, state resets %ld, IMU samples rejected %ld,"
               " gaps %ld; ZUPTs %ld (%ld skipped: moving off); final status %s\n  %.3f s (%.0f IMU samples/s) -> %s\n",
               what, imu_samples, t0, t1, fixes, init.c_str(), ft.gate_rejections, ft.gate_resyncs, ft.fixes_retracted,
               ft.late_dropped, ft.covariance_resets, ft.state_resets, ft.imu_rejected, ft.imu_gaps, ft.zupts_applied,
               ft.zupts_skipped_moving, est::describe_status(f.status()).c_str(), elapsed,
               imu_samples / std::max(elapsed, 1e-9), nav_path.c_str());
  if (f.options().adapt_imu_noise) {
    const est::ImuNoiseScale run = f.imu_noise_psd_scale(), floor = f.imu_noise_floor();
    char measured[96];
    if (standstill_s > 0)
      std::snprintf(measured, sizeof measured, "a %.0f s standstill in the data showed gyro %.1fx, accel %.1fx: the floor",
                    standstill_s, floor.gyro, floor.accel);
    else
      std::snprintf(measured, sizeof measured, "no standstill in the data to measure it over: floor 1x");
    char peak[96] = "";
    if (f.imu_noise_peak().scale > f.imu_noise_scale())
      std::snprintf(peak, sizeof peak, ", at most %.3g at %.1f s", f.imu_noise_peak().scale, f.imu_noise_peak().t_s);
    std::fprintf(
        stderr,
        "  IMU noise as installed: gyro %.1fx, accel %.1fx the configured PSD at the end (%s; times %.2f adapted "
        "to the GNSS position NIS%s; %ld fixes down-weighted by the robust update)\n",
        run.gyro, run.accel, measured, f.imu_noise_scale(), peak, ft.downweighted);
    if (f.options().split_noise_adaptation) {
      const est::NoiseAdaptation& na = f.noise_adaptation();
      for (int c = 0; c < est::NoiseAdaptation::kGnssClasses; ++c) {
        if (na.gnss_fixes(c) == 0) continue;
        const double configured = f.options().gnss_variance_scale[c];
        char on_top[120] = "";
        if (configured != 1.0)
          std::snprintf(on_top, sizeof on_top, " on top of the configured %.3g (ldv.gnss_variance_scale)", configured);
        std::fprintf(stderr,
                     "  GNSS noise: %s solutions' position variance times %.2f +- %.2f the stated (std times %.2f)%s "
                     "at the end, estimated over %ld fixes apart from the IMU's\n",
                     est::NoiseAdaptation::gnss_class_name(c), na.gnss_scale(c), na.gnss_scale_sigma(c),
                     std::sqrt(na.gnss_scale(c)), on_top, na.gnss_fixes(c));
      }
      std::fprintf(stderr, "  GNSS position innovations: lag-1 correlation %.2f (white: within +-%.2f)\n",
                   na.lag1_correlation(), 3.0 / std::sqrt(std::max<double>(na.lag1_products(), 1.0)));
    }
  }
}

// A forward run written over an earlier smoothed one's name: its separation file would make `ldv report` show
// a smoothing section that is not this run's. Only a file ldv smooth wrote (its header) is removed; the forward
// files stay (they may be anyone's), and without the separation the report does not take them.
void remove_stale_smoothing_outputs(const std::string& nav_path) {
  const std::string f = cli::output_base(nav_path) + "_separation.txt";
  std::error_code ec;
  if (!fs::is_regular_file(f, ec)) return;
  std::string first;
  std::getline(std::ifstream(f) >> std::ws, first);
  if (first.rfind(cli::kSeparationHeaderStart, 0) == 0 && fs::remove(f, ec))
    std::fprintf(stderr, "ldv nav: removed %s (an earlier ldv smooth's output under this name)\n", f.c_str());
}

// The backward pass in numbers, and the separation QC: forward minus smoothed against its expected envelope.
void print_smoothing_summary(const est::SmoothedRun& run, const est::RtsRecorder& rec, double forward_s,
                             const std::string& forward_path) {
  long beyond = 0, rows = 0;
  double max_sep_h_m = 0.0, t_max = 0.0;
  for (std::size_t i = 0; i < run.size(); i += 10) {
    const est::SmoothedRow r = run.row(i);
    const double h = r.separation.head<2>().norm();
    if (h > max_sep_h_m) {
      max_sep_h_m = h;
      t_max = r.forward.t_s;
    }
    for (int k = 0; k < 3; ++k) {
      if (r.std_separation(k) <= 1e-4) continue;  // no separation expected (the run's end, a restart)
      beyond += std::abs(r.separation(k)) > 3.0 * r.std_separation(k);
      ++rows;
    }
  }
  std::fprintf(stderr,
               "ldv smooth: smoothed over %zu covariance epochs (%.0f MB of records on disk; forward pass %.1f s, "
               "forward solution -> %s)\n  separation (forward - smoothed): largest horizontal %.3f m at %.3f s; "
               "%.2f %% of position components beyond 3 sigma of the expected separation\n",
               run.epochs().size(), rec.bytes_on_disk() / 1e6, forward_s, forward_path.c_str(), max_sep_h_m, t_max,
               rows > 0 ? 100.0 * beyond / rows : 0.0);
}

// Command-line alignment settings override the configuration's ldv: keys.
void apply_alignment_args(const NavArgs& a, est::FilterOptions& opt) {
  if (a.align_speed_mps > 0) opt.align_speed_mps = a.align_speed_mps;
  if (a.align_hypotheses > 0) opt.align_hypotheses = a.align_hypotheses;
}

// Builds the filter once to validate the model (unknown model or effect names -> InputError).
std::unique_ptr<est::NavFilter> check_model(const NavArgs& a, const est::FilterOptions& opt) {
  try {
    return std::make_unique<est::NavFilter>(opt);
  } catch (const std::invalid_argument& e) {
    throw InputError(a.in.config.empty() ? "ldv nav" : a.in.config, 0, e.what());
  }
}

// Rows not written because their time was not after the last one (a time_offset estimate stepping back).
void warn_rows_not_advancing(const cli::NavOutputs& out, const std::string& path, bool quiet) {
  if (out.rows_not_advancing() > 0 && !quiet)
    std::fprintf(stderr,
                 "ldv nav: WARNING: %ld epochs not written to %s: their time (IMU time + the time_offset estimate) was "
                 "not after the row before (the estimate stepped back)\n",
                 out.rows_not_advancing(), path.c_str());
}

void run_lcm_log(const NavArgs& a, const KfGinsConfig& cfg, est::FilterOptions opt, const est::AlignmentOptions& ao) {
  const auto t_begin = std::chrono::steady_clock::now();
  opt.history_s = a.history_s;  // as the live service: late fixes re-process the IMU history
  est::SessionOptions so = live_session_options(cfg, opt, &ao);
  so.align_wait_s = a.align_wait_s;
  FusionEngine engine(so);
  const std::string nav_path = default_nav_path(a, cfg);
  std::unique_ptr<cli::NavOutputs> out;
  long n = 0;
  double t0 = 0, t1 = 0;
  // Each epoch written when the session navigates it (with the filter of that moment: the backlog released at
  // the alignment is many epochs in one call).
  engine.set_epoch_observer([&](const est::NavFilter& f, int gps_week) {
    if (!out) {
      out = std::make_unique<cli::NavOutputs>(nav_path, f, a.std_rate_hz);
      t0 = f.state().t_s;
    }
    for (const auto& r : engine.filter().take_innovations()) out->innovation(r);
    out->epoch(f, a.week >= 0 ? a.week : gps_week);
    t1 = f.state().t_s;
    ++n;
  });
  const LogReplaySummary sum = replay_fusion_log(
      a.lcm_log, engine, [](const FusionOutput&) {}, "IMU", "GNSS_SOLUTION", a.host_clock_imu);
  if (!out) throw InputError(a.lcm_log, 0, "no navigation output: the log never allowed an alignment (" +
                                               std::to_string(sum.imu_messages) + " IMU and " +
                                               std::to_string(sum.gnss_messages) + " GNSS messages)");
  out->close();
  warn_rows_not_advancing(*out, nav_path, a.quiet);
  out.reset();
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_begin).count();
  if (!a.quiet) {
    std::fprintf(
        stderr,
        "ldv nav: LCM log: %ld IMU, %ld GNSS, %ld wheel speed, %ld malformed, %ld other messages, %ld corrupt log "
        "events\n",
        sum.imu_messages, sum.gnss_messages, sum.wheel_messages, sum.malformed, sum.other_messages,
        sum.corrupt_log_events);
    print_summary("replayed through FusionEngine", n, t0, t1, sum.gnss_messages, sum.initialisation, engine.filter(),
                  elapsed, nav_path, engine.session().noise_standstill_s());
    if (const long late = engine.filter().faults().late_dropped; late > 0)
      std::fprintf(stderr,
                   "ldv nav: WARNING: %ld measurements arrived later than the IMU history kept (--history %.1f s) and "
                   "were not used; a larger --history takes them (as the live service's history_s)\n",
                   late, a.history_s);
    if (const est::ImuLatencyWindow* w = engine.session().imu_latency_window()) {
      for (const est::ImuLatencyDecision& d : w->decisions())
        std::fprintf(stderr,
                     "ldv nav: IMU stamps late by %.1f +- %.1f ms (live window up to %.3f s), taken out from %.3f s on\n",
                     1e3 * d.lag_s, 1e3 * d.sigma_s, d.window_end_s, d.from_imu_t_s);
      if (w->decisions().empty())
        std::fprintf(stderr, "ldv nav: IMU latency looked for live: %d window estimates, none significant\n",
                     w->estimates());
    }
  }
}

// The IMU and GNSS as the filter takes them (a tagged CSV's rates integrated, the stamps' latency and the
// calibration applied, .pos solutions converted), as KF-GINS imu.txt and gnss.txt: what another tool (KF-GINS
// itself) needs to run on the same data side by side.
void write_filter_inputs(const assess::NavInputs& in, const std::string& dir, bool quiet) {
  fs::create_directories(dir);
  const std::string imu = (fs::path(dir) / "imu.txt").string(), gnss = (fs::path(dir) / "gnss.txt").string();
  write_kfgins_imu(imu, in.imu);
  bool velocity = !in.gnss.empty();
  for (const GnssFix& f : in.gnss) velocity &= f.has_velocity;
  write_kfgins_gnss(gnss, in.gnss, velocity);
  if (!quiet) std::fprintf(stderr, "ldv nav: the filter's inputs written: %s, %s\n", imu.c_str(), gnss.c_str());
}

void run_nav(const NavArgs& a) {
  const bool imu_given = !a.in.imu.empty() || !a.in.imu_csv.empty();
  const bool gnss_given = !a.in.gnss.empty() || !a.in.rtklib_pos.empty();
  if (!a.in.imu.empty() && !a.in.imu_csv.empty()) throw InputError("ldv nav", 0, "give one of --imu and --imu-csv");
  if (!a.in.gnss.empty() && !a.in.rtklib_pos.empty()) throw InputError("ldv nav", 0, "give one of --gnss and --pos");
  if (!a.lcm_log.empty() && (imu_given || gnss_given))
    throw InputError("ldv nav", 0, "--lcm-log holds both IMU and GNSS: do not combine it with --imu/--gnss/--pos");
  if (!a.in.imu_tag.empty() && a.in.imu_csv.empty()) throw InputError("ldv nav", 0, "--imu-tag goes with --imu-csv");
  if (!a.in.calibration.empty() && !a.lcm_log.empty())
    throw InputError("ldv nav", 0, "--calibration goes with IMU files: a log's IMU messages are imu_acq's, already calibrated "
                                   "by its calibration_file");
  if (a.in.config.empty() && a.lcm_log.empty() && (!imu_given || !gnss_given))
    throw InputError("ldv nav", 0,
                     "give --kfgins-config FILE, or an IMU input (--imu FILE or --imu-csv FILE) and a GNSS input "
                     "(--gnss FILE or --pos FILE), or --lcm-log FILE");

  if (!a.lcm_log.empty() && a.smooth)
    throw InputError(a.lcm_log, 0, "smoothing works on files: `ldv export` the log to files first");
  if (!a.lcm_log.empty()) {
    assess::NavInputs model = assess::load_nav_model(a.in);
    apply_alignment_args(a, model.options);
    check_model(a, model.options);
    if (!a.quiet && a.print_options) model.options.print(std::cerr);
    run_lcm_log(a, model.config, model.options, est::alignment_options_from(model.options));
    return;
  }

  const auto t_begin = std::chrono::steady_clock::now();
  assess::NavInputs in = assess::load_nav_inputs(a.in);
  est::FilterOptions& opt = in.options;
  apply_alignment_args(a, opt);
  std::unique_ptr<est::NavFilter> filter = check_model(a, opt);
  if (!a.quiet && a.print_options) opt.print(std::cerr);
  const est::AlignmentOptions ao = est::alignment_options_from(opt);

  int week = a.week;
  if (week < 0) week = week_from_config(in.config);
  if (week < 0) week = in.gps_week >= 0 ? in.gps_week : 0;
  const std::string nav_path = default_nav_path(a, in.config);
  if (!a.quiet) {
    const std::string gnss_note = in.gnss_note.empty() ? "" : " (" + in.gnss_note + ")";
    std::fprintf(stderr, "ldv nav: %zu IMU samples (%s), %zu GNSS fixes%s\n", in.imu.size(), in.imu_note.c_str(),
                 in.gnss.size(), gnss_note.c_str());
    if (!in.gnss_velocity_note.empty()) std::fprintf(stderr, "ldv nav: %s\n", in.gnss_velocity_note.c_str());
    for (const std::string& line : assess::input_count_lines(in)) std::fprintf(stderr, "  %s\n", line.c_str());
    std::fprintf(stderr, "state layout (%d states):\n%s", filter->layout().size(), filter->layout().describe().c_str());
  }
  for (const std::string& w : assess::input_warnings(in)) std::fprintf(stderr, "ldv nav: WARNING: %s\n", w.c_str());
  if (!a.write_inputs.empty()) write_filter_inputs(in, a.write_inputs, a.quiet);

  // Smoothing: the forward solution beside the smoothed one, which takes the --out name.
  const std::string forward_path = a.smooth ? cli::output_base(nav_path) + "_forward.nav" : nav_path;
  if (!a.smooth) remove_stale_smoothing_outputs(nav_path);
  cli::NavOutputs out(forward_path, *filter, a.std_rate_hz);
  std::unique_ptr<est::RtsRecorder> recorder;
  if (a.smooth) {
    recorder = std::make_unique<est::RtsRecorder>(*filter);
    filter->set_observer(recorder.get());
  }
  est::RunCallbacks cb;
  cb.on_epoch = [&](const est::NavFilter& f) {
    out.epoch(f, week);
    if (recorder) recorder->add_row(f, week);
  };
  cb.on_innovation = [&](const est::InnovationRecord& r) { out.innovation(r); };
  const bool show_progress = !a.quiet && in.imu.size() > 100000;
  const char* pass = a.smooth ? "ldv smooth: forward" : "ldv nav:";
  auto progress = [&pass](double done) { std::fprintf(stderr, "\r%s %3.0f %%", pass, done * 100.0); };
  if (show_progress) cb.on_progress = progress;

  const est::RunSummary sum = est::run_navigation(in.imu, in.gnss, in.config, *filter, cb, &ao, &in.other_observations);
  out.close();
  warn_rows_not_advancing(out, forward_path, a.quiet);
  const double forward_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_begin).count();
  if (recorder) {
    pass = "ldv smooth: backward";
    const est::SmoothedRun run = recorder->smooth(show_progress ? std::function<void(double)>(progress) : nullptr);
    pass = "ldv smooth: writing";
    cli::write_smoothed(run, filter->layout(), nav_path, a.std_rate_hz, filter->options().gyro_quantization_rad,
                        filter->error_model().time_offset_s,
                        show_progress ? std::function<void(double)>(progress) : nullptr);
    if (show_progress) std::fprintf(stderr, "\r%40s\r", "");
    if (!a.quiet) print_smoothing_summary(run, *recorder, forward_s, forward_path);
  }
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_begin).count();
  if (show_progress) std::fprintf(stderr, "\r");
  if (!a.quiet) {
    print_summary(a.smooth ? "files, smoothed" : "files", sum.imu_samples, sum.t_start_s, sum.t_end_s, sum.gnss_fixes,
                  sum.initialisation, *filter, elapsed, nav_path, sum.imu_noise_standstill_s);
    if (!sum.white_noise_filled.empty()) std::fprintf(stderr, "  %s\n", sum.white_noise_filled.c_str());
    const est::ImuStampJitter& j = in.imu_stamp_jitter.found ? in.imu_stamp_jitter : sum.imu_stamp_jitter;
    // (a simulator's or a device clock's tags: nothing to say)
    if (j.noticeable())
      std::fprintf(stderr,
                   "  IMU time tags: %.2f +- %.2f ms off the sensor's %.1f Hz sampling (%.0f %% of the rows repeat the "
                   "sample before): modelled, each increment's error the rate's change times the tag's\n",
                   1e3 * j.sigma_s, 1e3 * j.sigma_sigma_s, 1.0 / j.sample_interval_s, 100.0 * j.repeated_fraction);
  }
}

// `nav` and `smooth` take the same options (`smooth` = `nav --smooth`).
void add_nav_options(CLI::App* c, const std::shared_ptr<NavArgs>& args) {
  cli::add_nav_input_options(c, args->in);
  c->add_option(
      "--lcm-log", args->lcm_log,
      "replay an LCM log (IMU + GNSS_SOLUTION, and WHEEL_SPEED with --aid odometer) through the fusion service's "
      "navigation session");
  c->add_option("--history", args->history_s,
                "with --lcm-log: how late a GNSS fix may arrive [s] (as the live service)")
      ->check(ldv::cli::finite_range(0, 3600));
  c->add_flag("--host-clock-imu", args->host_clock_imu,
              "with --lcm-log: also use IMU samples stamped from the host clock (status bit 0), as fusion's "
              "host_clock_imu does for an IMU without PPS");
  c->add_option("--align-wait", args->align_wait_s, "with --lcm-log: host seconds the alignment waits for GNSS")
      ->check(ldv::cli::finite_range(0, 86400));
  c->add_option("--out", args->out, "output .nav (default <outputpath>/KF_GINS_Navresult.nav)");
  c->add_option(
      "--write-inputs", args->write_inputs,
      "also write the IMU and GNSS as the filter takes them, as KF-GINS imu.txt and gnss.txt into this folder "
      "(to run another tool on the same data)");
  c->add_option("--week", args->week, "GPS week written in the .nav (default ldv.week, the .pos week, or 0)")
      ->check(ldv::cli::finite_range(0, 9999));
  c->add_option("--std-rate", args->std_rate_hz, "rate of the _std.txt rows [Hz] (0: every IMU sample)")
      ->check(ldv::cli::finite_range(0, 1e4));
  c->add_option("--align-speed", args->align_speed_mps,
                "alignment without a given state: GNSS speed [m/s] above which the course gives the heading (default "
                "ldv.align_speed_mps, else 2)")
      ->check(ldv::cli::finite_range(0, 1000));
  c->add_option("--align-hypotheses", args->align_hypotheses,
                "unknown mounting (hand-held): try N body headings 360/N apart against the GNSS track (default "
                "ldv.align_hypotheses, else 1: body x along the motion; 12 for a hand-held IMU)")
      ->check(CLI::Range(0, 360));
  c->add_flag("--quiet", args->quiet, "no progress or summary on stderr");
  c->add_flag("--print-options", args->print_options, "print the filter options");
  c->callback([args] { run_nav(*args); });
}

void add_nav_command(CLI::App& app) {
  auto args = std::make_shared<NavArgs>();
  CLI::App* c = app.add_subcommand("nav", "GPS/INS error-state EKF over KF-GINS files (writes a KF-GINS .nav)");
  add_nav_options(c, args);
  c->add_flag("--smooth", args->smooth,
              "forward filter, then the Rauch-Tung-Striebel backward pass: the smoothed solution in --out, the "
              "forward one in FILE_forward.nav, forward minus smoothed in FILE_separation.txt (= ldv smooth)");
}

void add_smooth_command(CLI::App& app) {
  auto args = std::make_shared<NavArgs>();
  args->smooth = true;
  CLI::App* c = app.add_subcommand(
      "smooth",
      "post-processing: the GPS/INS filter forward, then the Rauch-Tung-Striebel smoother backward (writes the "
      "smoothed .nav, its _std.txt and _separation.txt, and the forward solution as FILE_forward.nav); the options "
      "of ldv nav");
  add_nav_options(c, args);
}

const ldv::cli::RegisterCommand kRegisterNavCommand{"nav", &add_nav_command};
const ldv::cli::RegisterCommand kRegisterSmooth{"smooth", &add_smooth_command};
}  // namespace
