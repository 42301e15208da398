// `ldv nav`: the GPS/INS filter over files (DESIGN.md section 2; estimator/README.md).
//   ldv nav --kfgins-config FILE.yaml [--model NAME] [--add EFFECT]... [--drop EFFECT]... [--out FILE.nav]
//   ldv nav --imu imu.txt --gnss gnss.txt [--lever x y z] ...
// Outputs: FILE.nav (KF-GINS layout, one line per IMU sample), FILE_std.txt, FILE_innovations.txt.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

#include "common/formats/kfgins_config.hpp"
#include "common/formats/kfgins_files.hpp"
#include "common/io/input_error.hpp"
#include "common/io/text_table.hpp"
#include "estimator/run/run_navigation.hpp"
#include "tools/ldv/command_registry.hpp"

namespace {
namespace fs = std::filesystem;
using namespace ldv;

struct NavArgs {
  std::string config, imu, gnss, out, model;
  std::vector<std::string> add, drop;
  std::vector<double> lever;
  int week = -1;
  double std_rate_hz = 10.0;
  bool quiet = false, print_options = false;
};

// Writes columns with fixed decimals fast (the std and innovation files).
class TextOut {
 public:
  TextOut(const std::string& path, const std::string& header) : f_(std::fopen(path.c_str(), "wb")), path_(path) {
    if (!f_) throw InputError(path, 0, "cannot open file for writing");
    std::setvbuf(f_, nullptr, _IOFBF, 1 << 20);
    std::fputs(header.c_str(), f_);
  }
  ~TextOut() { std::fclose(f_); }
  void num(double v, int decimals) {
    if (n_ > 0) buf_[n_++] = ' ';
    n_ += format_fixed(buf_ + n_, v, decimals);
  }
  void text(const char* s) {
    if (n_ > 0) buf_[n_++] = ' ';
    while (*s) buf_[n_++] = *s++;
  }
  void end_line() {
    buf_[n_++] = '\n';
    std::fwrite(buf_, 1, n_, f_);
    n_ = 0;
  }

 private:
  std::FILE* f_;
  std::string path_;
  char buf_[4096];
  int n_ = 0;
};

void run_nav(const NavArgs& a) {
  KfGinsConfig cfg;
  est::FilterOptions opt;
  if (!a.config.empty()) {
    cfg = load_kfgins_config(a.config);
    opt = est::options_from_kfgins(cfg);
  } else {
    if (a.imu.empty() || a.gnss.empty()) throw InputError("ldv nav", 0, "give --kfgins-config FILE, or --imu FILE and --gnss FILE");
    cfg.imu_path = a.imu;
    cfg.gnss_path = a.gnss;
    cfg.output_path = ".";
  }
  if (!a.imu.empty()) cfg.imu_path = a.imu;
  if (!a.gnss.empty()) cfg.gnss_path = a.gnss;
  if (a.lever.size() == 3) opt.lever_arm.init = Vec3(a.lever[0], a.lever[1], a.lever[2]);
  if (!a.model.empty()) opt.model = a.model;
  opt.add.insert(opt.add.end(), a.add.begin(), a.add.end());
  opt.drop.insert(opt.drop.end(), a.drop.begin(), a.drop.end());
  int week = a.week;
  if (week < 0) week = (cfg.ldv.IsDefined() && cfg.ldv["week"]) ? cfg.ldv["week"].as<int>() : 0;

  std::unique_ptr<est::NavFilter> filter;
  try {
    filter = std::make_unique<est::NavFilter>(opt);
  } catch (const std::invalid_argument& e) {
    throw InputError(a.config.empty() ? "ldv nav" : a.config, 0, e.what());
  }
  const auto t_begin = std::chrono::steady_clock::now();
  ImuReadReport imu_report;
  const std::vector<ImuIncrement> imu = read_kfgins_imu(cfg.imu_path, &imu_report);
  const std::vector<GnssFix> gnss = read_kfgins_gnss(cfg.gnss_path);

  std::string nav_path = a.out;
  if (nav_path.empty()) {
    fs::create_directories(cfg.output_path.empty() ? "." : cfg.output_path);
    nav_path = (fs::path(cfg.output_path.empty() ? "." : cfg.output_path) / "KF_GINS_Navresult.nav").string();
  }
  std::string base = nav_path;
  if (base.size() > 4 && base.substr(base.size() - 4) == ".nav") base.resize(base.size() - 4);
  if (!a.quiet) {
    std::fprintf(stderr, "ldv nav: %zu IMU samples (%ld duplicates skipped, %ld gaps), %zu GNSS fixes\n", imu.size(),
                 imu_report.skipped_duplicates, imu_report.gaps, gnss.size());
    std::fprintf(stderr, "state layout (%d states):\n%s", filter->layout().size(), filter->layout().describe().c_str());
    if (a.print_options) opt.print(std::cerr);
  }

  NavWriter nav_out(nav_path);
  std::string std_header =
      "# week sow std_pos_n std_pos_e std_pos_d [m] std_vel_n std_vel_e std_vel_d [m/s] std_roll std_pitch std_yaw [deg]";
  for (const auto& b : filter->layout().blocks())
    for (const auto& n : b.effect->state_names())
      std_header += std::string(" ") + n + "[" + b.effect->print_unit().unit + "]";
  std_header += " (each effect state: estimate then std)\n";
  TextOut std_out(base + "_std.txt", std_header);
  TextOut innov_out(base + "_innovations.txt",
                    "# t_sow kind innov_1 innov_2 innov_3 sqrtS_11 sqrtS_22 sqrtS_33 nis accepted(1/0) "
                    "(innovation = predicted - measured; position NED [m], velocity NED [m/s])\n");

  double next_std_t = -1e300;
  const double std_period = a.std_rate_hz > 0 ? 1.0 / a.std_rate_hz : 0.0;
  NavRecord rec;
  rec.week = week;
  est::RunCallbacks cb;
  cb.on_epoch = [&](const est::NavFilter& f) {
    const est::NavState& s = f.state();
    rec.sow_s = s.t_s;
    rec.pos = s.pos;
    rec.vel_n_mps = s.v_n_mps;
    rec.rpy_rad = s.rpy_rad();
    if (rec.rpy_rad.z() < 0) rec.rpy_rad.z() += 2.0 * kPi;  // KF-GINS prints yaw in [0, 360)
    nav_out.write(rec);
    if (s.t_s + 1e-9 >= next_std_t) {
      next_std_t = s.t_s + std_period;
      const Eigen::VectorXd sd = f.covariance().diagonal().cwiseSqrt();
      std_out.num(week, 0);
      std_out.num(s.t_s, 4);
      for (int i = 0; i < 6; ++i) std_out.num(sd(i), 5);
      for (int i = 6; i < 9; ++i) std_out.num(sd(i) * kRadToDeg, 6);
      for (const auto& b : f.layout().blocks()) {
        const double k = b.effect->print_unit().scale;
        for (int j = 0; j < b.dim; ++j) {
          std_out.num(f.effect_state()(b.offset - est::kNavDim + j) * k, 6);
          std_out.num(sd(b.offset + j) * k, 6);
        }
      }
      std_out.end_line();
    }
  };
  cb.on_innovation = [&](const est::InnovationRecord& r) {
    innov_out.num(r.t_s, 4);
    innov_out.text(est::measurement_name(r.kind));
    for (int i = 0; i < 3; ++i) innov_out.num(r.innovation(i), 5);
    for (int i = 0; i < 3; ++i) innov_out.num(std::sqrt(r.S(i, i)), 5);
    innov_out.num(r.nis, 3);
    innov_out.num(r.accepted ? 1 : 0, 0);
    innov_out.end_line();
  };
  const bool show_progress = !a.quiet && imu.size() > 100000;
  if (show_progress)
    cb.on_progress = [](double done) { std::fprintf(stderr, "\rldv nav: %3.0f %%", done * 100.0); };

  const est::RunSummary sum = est::run_navigation(imu, gnss, cfg, *filter, cb);
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_begin).count();
  if (show_progress) std::fprintf(stderr, "\r");
  if (!a.quiet) {
    const auto& ft = sum.faults;
    std::fprintf(stderr,
                 "ldv nav: %ld IMU samples from %.3f to %.3f s, %ld GNSS fixes; initial state: %s\n"
                 "  gate rejections %ld (resyncs %ld), covariance resets %ld, state resets %ld, IMU samples rejected %ld,"
                 " gaps %ld; final status %s\n  %.3f s (%.0f IMU samples/s) -> %s\n",
                 sum.imu_samples, sum.t_start_s, sum.t_end_s, sum.gnss_fixes, sum.initialisation.c_str(),
                 ft.gate_rejections, ft.gate_resyncs, ft.covariance_resets, ft.state_resets, ft.imu_rejected, ft.imu_gaps,
                 est::describe_status(sum.final_status).c_str(), elapsed, sum.imu_samples / elapsed, nav_path.c_str());
  }
}

void add_nav_command(CLI::App& app) {
  auto args = std::make_shared<NavArgs>();
  CLI::App* c = app.add_subcommand("nav", "GPS/INS error-state EKF over KF-GINS files (writes a KF-GINS .nav)");
  c->add_option("--kfgins-config", args->config, "KF-GINS YAML configuration (paths, rates, init state, imunoise, antlever)");
  c->add_option("--imu", args->imu, "IMU increments (KF-GINS imu.txt), overrides the config");
  c->add_option("--gnss", args->gnss, "GNSS solutions (7- or 13-column KF-GINS gnss.txt), overrides the config");
  c->add_option("--model", args->model, "ins15 | kfgins21 | geoldv51 (default kfgins21 or ldv.model)");
  c->add_option("--add", args->add, "add an effect block (repeatable)");
  c->add_option("--drop", args->drop, "drop an effect block (repeatable)");
  c->add_option("--out", args->out, "output .nav (default <outputpath>/KF_GINS_Navresult.nav)");
  c->add_option("--lever", args->lever, "antenna lever arm x y z [m], body front-right-down")->expected(3);
  c->add_option("--week", args->week, "GPS week written in the .nav (default ldv.week or 0)");
  c->add_option("--std-rate", args->std_rate_hz, "rate of the _std.txt rows [Hz] (0: every IMU sample)");
  c->add_flag("--quiet", args->quiet, "no progress or summary on stderr");
  c->add_flag("--print-options", args->print_options, "print the filter options");
  c->callback([args] { run_nav(*args); });
}

const ldv::cli::RegisterCommand kRegister{"nav", &add_nav_command};
}  // namespace
