// `ldv calib static`: multi-position static IMU calibration (toolbox/calib/README.md).
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <sstream>

#include "common/io/input_error.hpp"
#include "common/logging.hpp"
#include "toolbox/calib/calib_report.hpp"
#include "toolbox/calib/static_calibration.hpp"
#include "tools/ldv/cli_checks.hpp"
#include "tools/ldv/command_registry.hpp"

namespace {

using namespace ldv::calib;

struct CalibStaticArgs {
  std::string file, acc_file, gyro_file, format = "auto";
  std::string acc_units = "m/s^2", gyro_units = "rad/s";
  double acc_counts_per_unit = 1.0, acc_offset_counts = 0.0;
  double gyro_counts_per_unit = 1.0, gyro_offset_counts = 0.0, gyro_full_scale = 0.0;
  double rate_hz = 0.0;
  std::string columns;
  double lat_deg = 45.0, height_m = 0.0, gravity_mps2 = 0.0;
  double init_static_s = 0.0, window_s = 1.0, min_pose_s = 2.0, threshold_multiplier = 0.0;
  std::string gyro_method = "auto", ev = "auto";
  std::string json_path, out_path, plot_prefix;
};

std::vector<std::string> split_list(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ',')) out.push_back(item);
  return out;
}

ImuLog read_log(const CalibStaticArgs& a) {
  ImuLogOptions o;
  o.accel = {a.acc_counts_per_unit, a.acc_offset_counts, accel_si_per_unit(a.acc_units)};
  o.gyro = {a.gyro_counts_per_unit, a.gyro_offset_counts, gyro_si_per_unit(a.gyro_units)};
  if (a.rate_hz > 0.0) o.rate_hz = a.rate_hz;
  if (!a.columns.empty()) o.columns = split_list(a.columns);
  std::string format = a.format;
  if (format == "auto") format = !a.acc_file.empty() ? "xyz" : "csv";
  if (format == "xyz") {
    if (a.acc_file.empty()) throw ldv::InputError("--acc", 0, "format xyz needs --acc FILE (and --gyro FILE)");
    return read_xyz_pair(a.acc_file, a.gyro_file, o);
  }
  if (a.file.empty()) throw ldv::InputError("FILE", 0, "give a log FILE, or --acc/--gyro files");
  if (format == "csv") return read_csv_log(a.file, o);
  if (format == "kfgins") return read_kfgins_log(a.file);
  throw ldv::InputError("--format", 0, "unknown format '" + format + "' (auto, xyz, csv, kfgins)");
}

int run_calib_static(const CalibStaticArgs& a) {
  const ImuLog log = read_log(a);
  StaticCalibrationOptions opt;
  opt.detector.init_static_s = a.init_static_s;
  opt.detector.window_s = a.window_s;
  opt.detector.min_pose_s = a.min_pose_s;
  opt.detector.threshold_multiplier = a.threshold_multiplier;
  opt.lat_rad = a.lat_deg * ldv::kDegToRad;
  opt.h_m = a.height_m;
  if (a.gravity_mps2 > 0.0) opt.gravity_mps2 = a.gravity_mps2;
  opt.gyro_method = parse_gyro_method(a.gyro_method);
  opt.gyro_full_scale_rad_s = a.gyro_full_scale * gyro_si_per_unit(a.gyro_units);
  if (a.ev != "auto") {
    char* end = nullptr;
    const double ev = std::strtod(a.ev.c_str(), &end);
    if (end == a.ev.c_str() || *end != '\0' || !(ev >= 0.0))
      throw ldv::InputError("--ev", 0, "expected 'auto' or a non-negative number, found '" + a.ev + "'");
    opt.ev = ev;
  }
  const StaticCalibrationResult r = calibrate_static(log, opt);
  print_report(stdout, r, log);
  if (!a.json_path.empty()) write_json(a.json_path, r, log);
  if (!a.plot_prefix.empty())
    for (const std::string& png : write_sweep_plots(a.plot_prefix, r)) std::printf("plot: %s\n", png.c_str());
  if (!r.ok()) {
    std::fprintf(stderr, "ldv calib static: accelerometer not calibrated: %s\n", r.accel.refusal.c_str());
    return 3;
  }
  if (!a.out_path.empty()) {
    save_calibration(a.out_path, r.calibration);
    std::printf("calibration written to %s\n", a.out_path.c_str());
  }
  return 0;
}

void add_calib_command(CLI::App& app) {
  CLI::App* calib = app.add_subcommand("calib", "IMU calibration");
  calib->require_subcommand(1);
  auto args = std::make_shared<CalibStaticArgs>();
  CLI::App* st = calib->add_subcommand("static", "multi-position static calibration (gravity / Earth-rate magnitude, "
                                                 "Gauss-Helmert; gyro by rotation between poses for MEMS)");
  st->add_option("file", args->file, "one log file (csv with header, or kfgins increments)");
  st->add_option("--acc", args->acc_file, "accelerometer file `t x y z` (with --gyro: format xyz)");
  st->add_option("--gyro", args->gyro_file, "gyro file `t x y z`");
  st->add_option("--format", args->format, "auto | xyz | csv | kfgins")->capture_default_str();
  st->add_option("--acc-units", args->acc_units, "accelerometer unit after dividing by counts: m/s^2 | g")
      ->capture_default_str();
  st->add_option("--acc-counts-per-unit", args->acc_counts_per_unit, "nominal counts per acc unit (1: not counts)")
      ->capture_default_str()
      ->check(ldv::cli::finite_positive(1e12));
  st->add_option("--acc-offset-counts", args->acc_offset_counts, "raw zero offset removed first (e.g. 32768)")
      ->check(ldv::cli::finite_range(-1e12, 1e12));
  st->add_option("--gyro-units", args->gyro_units, "rad/s | deg/s | deg/h")->capture_default_str();
  st->add_option("--gyro-counts-per-unit", args->gyro_counts_per_unit, "nominal counts per gyro unit")
      ->capture_default_str()
      ->check(ldv::cli::finite_positive(1e12));
  st->add_option("--gyro-offset-counts", args->gyro_offset_counts, "raw zero offset removed first")
      ->check(ldv::cli::finite_range(-1e12, 1e12));
  st->add_option("--gyro-full-scale", args->gyro_full_scale,
                 "gyro range in --gyro-units (e.g. 250 deg/s); motions that reach it are left out (0: detect)")
      ->check(ldv::cli::finite_positive(1e12));
  st->add_option("--rate", args->rate_hz, "sample rate [Hz] (default: time column or file header)")
      ->check(ldv::cli::finite_positive(1e6));
  st->add_option("--columns", args->columns, "csv column names, e.g. t,ax,ay,az,gx,gy,gz ('-' skips one)");
  st->add_option("--lat-deg", args->lat_deg, "latitude for normal gravity and Earth rate")
      ->capture_default_str()
      ->check(ldv::cli::finite_range(-90, 90));
  st->add_option("--height-m", args->height_m, "ellipsoidal height")
      ->capture_default_str()
      ->check(ldv::cli::finite_range(-12000, 100000));
  st->add_option("--gravity", args->gravity_mps2, "local gravity magnitude [m/s^2] (overrides normal gravity)")
      ->check(ldv::cli::finite_range(9.7, 9.9));
  st->add_option("--init-static-s", args->init_static_s, "initial static period (default: file header or 30 s)")
      ->check(ldv::cli::finite_range(0, 1e6));
  st->add_option("--window-s", args->window_s, "variance window of the detector")
      ->capture_default_str()
      ->check(ldv::cli::finite_positive(1e5));
  st->add_option("--min-pose-s", args->min_pose_s, "shortest static pose kept")
      ->capture_default_str()
      ->check(ldv::cli::finite_range(0, 1e5));
  st->add_option("--threshold-mult", args->threshold_multiplier, "detector threshold multiplier (0: search 2..10)")
      ->check(ldv::cli::finite_range(0, 1e3));
  st->add_option("--gyro-method", args->gyro_method, "auto | earth-rate | rotation | none")->capture_default_str();
  st->add_option("--ev", args->ev, "damping constant EV: auto (sweep, minimum MSE) or a value")->capture_default_str();
  st->add_option("--json", args->json_path, "write the full result as JSON");
  st->add_option("-o,--out", args->out_path, "write the calibration YAML that ldv nav / imu_acq apply");
  st->add_option("--plot", args->plot_prefix, "write PREFIX_*_ev_sweep.{dat,gp,png} (gnuplot)");
  st->callback([args]() {
    const int rc = run_calib_static(*args);
    if (rc != 0) throw CLI::RuntimeError(rc);
  });
}

const ldv::cli::RegisterCommand kRegisterCalibCommand{"calib", &add_calib_command};

}  // namespace
