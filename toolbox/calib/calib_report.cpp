#include "toolbox/calib/calib_report.hpp"

#include "common/plot/gnuplot.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include "common/io/input_error.hpp"
#include "common/io/output_file.hpp"
#include "common/logging.hpp"

namespace ldv::calib {

namespace {

double rms(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x * x;
  return v.empty() ? 0.0 : std::sqrt(s / v.size());
}

void print_adjustment(std::FILE* out, const Adjustment& a) {
  if (!a.attempted) return;
  std::fprintf(out, "\n== %s ==\n", a.name.c_str());
  const ObservabilityReport& ob = a.undamped_observability;
  std::fprintf(out, "observability: condition number %.3g of the standardised normal matrix%s%s\n",
               ob.condition_number, ob.rank_deficient ? ", RANK DEFICIENT" : "",
               ob.unresolved && !ob.rank_deficient ? ", some directions unresolved" : "");
  for (const std::string& d : ob.weak_directions) std::fprintf(out, "  weak direction: %s\n", d.c_str());
  if (!a.solved) {
    std::fprintf(out, "NOT SOLVED: %s\n", a.refusal.c_str());
    return;
  }
  const GaussHelmertResult& r = a.result;
  std::fprintf(out, "converged in %d iterations; redundancy %d; sigma0 %.4g (a posteriori std of unit weight;"
               " 1 = residuals as the pose scatter predicts)\n", r.iterations, r.redundancy, r.sigma0);
  if (!a.sweep.points.empty()) {
    const DampingPoint& p0 = a.sweep.points.front();
    const DampingPoint* pc = nullptr;
    for (const DampingPoint& p : a.sweep.points)
      if (p.ev == a.ev) pc = &p;
    std::fprintf(out, "damping EV sweep 0..%.2f: max covariance eigenvalue %.3g -> %.3g, rms residual %.4g -> %.4g %s\n",
                 a.sweep.points.back().ev, p0.max_cov_eigenvalue, a.sweep.points.back().max_cov_eigenvalue,
                 p0.rms_misclosure, a.sweep.points.back().rms_misclosure, a.residual_unit.c_str());
    std::fprintf(out, "chosen EV %.4g (%s)", a.ev, pc && pc == &a.sweep.best() ? "minimum estimated MSE" : "given");
    if (pc) {
      double worst = 0.0;
      const VectorXd s = r.sigma();
      for (int i = 0; i < pc->bias.size(); ++i)
        if (s[i] > 0) worst = std::max(worst, std::abs(pc->bias[i]) / s[i]);
      std::fprintf(out, ": bias it adds up to %.3g sigma of a parameter\n", worst);
    } else {
      std::fprintf(out, "\n");
    }
  }
  std::fprintf(out, "%-22s %16s %14s %8s", "parameter", "value", "sigma", "unit");
  if (!a.sweep.points.empty()) std::fprintf(out, " %14s", "EV bias");
  std::fprintf(out, "\n");
  const VectorXd s = r.sigma();
  const DampingPoint* pc = nullptr;
  for (const DampingPoint& p : a.sweep.points)
    if (p.ev == a.ev) pc = &p;
  for (size_t i = 0; i < a.param_names.size(); ++i) {
    const double k = a.param_display_scale[i];
    std::fprintf(out, "%-22s %16.6g %14.4g %8s", a.param_names[i].c_str(), r.x[i] * k, s[i] * k,
                 a.param_units[i].c_str());
    if (pc) std::fprintf(out, " %14.4g", pc->bias[i] * k);
    std::fprintf(out, "\n");
  }
  std::fprintf(out, "correlation matrix (x100):\n");
  const MatrixXd c = r.correlation();
  for (int i = 0; i < c.rows(); ++i) {
    std::fprintf(out, "  %-22s", a.param_names[i].c_str());
    for (int j = 0; j <= i; ++j) std::fprintf(out, " %4.0f", 100.0 * c(i, j));
    std::fprintf(out, "\n");
  }
  std::fprintf(out, "residual per %s [%s] (normalised by its a priori sigma):\n",
               a.block_labels.size() && a.block_labels[0].find("->") != std::string::npos ? "transition" : "pose",
               a.residual_unit.c_str());
  const double unit = a.residual_unit == "deg/h" ? kRadToDeg * 3600.0 : 1.0;
  for (size_t k = 0; k < r.misclosure.size(); ++k) {
    std::fprintf(out, "  %-8s", a.block_labels[k].c_str());
    for (int i = 0; i < r.misclosure[k].size(); ++i)
      std::fprintf(out, " %12.4g (%6.2f)", r.misclosure[k][i] * unit, r.normalised_misclosure[k][i]);
    std::fprintf(out, "\n");
  }
}

struct Json {
  std::ostringstream s;
  static std::string num(double v) {
    if (!std::isfinite(v)) return "null";
    char b[32];
    std::snprintf(b, sizeof b, "%.10g", v);
    return b;
  }
  static std::string str(const std::string& v) {
    std::string o = "\"";
    for (char c : v) {
      if (c == '"' || c == '\\') o += '\\';
      if (static_cast<unsigned char>(c) < 0x20) continue;
      o += c;
    }
    return o + "\"";
  }
  template <class V>
  static std::string arr(const V& v) {
    std::string o = "[";
    for (int i = 0; i < static_cast<int>(v.size()); ++i) o += (i ? ", " : "") + num(v[i]);
    return o + "]";
  }
};

std::string json_triad(const TriadCalibration& t, const char* bias_unit) {
  std::ostringstream s;
  s << "{\"bias_" << bias_unit << "\": " << Json::arr(t.bias) << ", \"bias_" << bias_unit
    << "_sigma\": " << Json::arr(t.bias_sigma) << ", \"scale\": " << Json::arr(t.scale)
    << ", \"scale_sigma\": " << Json::arr(t.scale_sigma) << ", \"misalignment_rad\": " << Json::arr(t.misalignment_rad)
    << ", \"misalignment_rad_sigma\": " << Json::arr(t.misalignment_sigma_rad)
    << ", \"frame_rotation_rad\": " << Json::arr(t.frame_rotation_rad)
    << ", \"frame_rotation_rad_sigma\": " << Json::arr(t.frame_rotation_sigma_rad) << "}";
  return s.str();
}

std::string json_adjustment(const Adjustment& a) {
  std::ostringstream s;
  s << "{\"name\": " << Json::str(a.name) << ", \"attempted\": " << (a.attempted ? "true" : "false")
    << ", \"solved\": " << (a.solved ? "true" : "false") << ", \"refusal\": " << Json::str(a.refusal);
  const ObservabilityReport& ob = a.undamped_observability;
  s << ", \"rank_deficient\": " << (ob.rank_deficient ? "true" : "false")
    << ", \"unresolved\": " << (ob.unresolved ? "true" : "false")
    << ", \"condition_number\": " << Json::num(ob.condition_number) << ", \"weak_directions\": [";
  for (size_t i = 0; i < ob.weak_directions.size(); ++i) s << (i ? ", " : "") << Json::str(ob.weak_directions[i]);
  s << "]";
  if (a.solved) {
    const GaussHelmertResult& r = a.result;
    s << ", \"ev\": " << Json::num(a.ev) << ", \"sigma0\": " << Json::num(r.sigma0)
      << ", \"redundancy\": " << r.redundancy << ", \"parameters\": [";
    const VectorXd sg = r.sigma();
    for (size_t i = 0; i < a.param_names.size(); ++i)
      s << (i ? ", " : "") << "{\"name\": " << Json::str(a.param_names[i]) << ", \"value_si\": " << Json::num(r.x[i])
        << ", \"sigma_si\": " << Json::num(sg[i]) << "}";
    s << "], \"correlation\": [";
    const MatrixXd c = r.correlation();
    for (int i = 0; i < c.rows(); ++i) {
      std::vector<double> row(c.cols());
      for (int j = 0; j < c.cols(); ++j) row[j] = c(i, j);
      s << (i ? ", " : "") << Json::arr(row);
    }
    s << "], \"residual_unit_si\": " << Json::str(a.residual_unit == "deg/h" ? "rad/s" : a.residual_unit)
      << ", \"residuals\": [";
    for (size_t k = 0; k < r.misclosure.size(); ++k) s << (k ? ", " : "") << Json::arr(r.misclosure[k]);
    s << "], \"ev_sweep\": [";
    for (size_t i = 0; i < a.sweep.points.size(); ++i) {
      const DampingPoint& p = a.sweep.points[i];
      s << (i ? ", " : "") << "{\"ev\": " << Json::num(p.ev) << ", \"max_cov_eigenvalue\": "
        << Json::num(p.max_cov_eigenvalue) << ", \"sigma0\": " << Json::num(p.sigma0)
        << ", \"rms_residual\": " << Json::num(p.rms_misclosure) << ", \"mse\": " << Json::num(p.mse)
        << ", \"bias_si\": " << Json::arr(p.bias) << "}";
    }
    s << "]";
  }
  s << "}";
  return s.str();
}

}  // namespace

void print_report(std::FILE* out, const StaticCalibrationResult& r, const ImuLog& log) {
  std::fprintf(out, "ldv calib static: %s\n", log.source.c_str());
  std::fprintf(out, "%zu samples, dt %.6g s, %.1f s; gravity %.6f m/s^2\n", log.size(), log.dt_s,
               log.size() * log.dt_s, r.gravity_mps2);
  if (!r.threshold_trials.empty()) {
    std::fprintf(out, "threshold multiplier search (imu_tk): k poses residual_std[m/s^2]\n");
    for (const ThresholdTrial& t : r.threshold_trials)
      std::fprintf(out, "  %4.0f %5zu %12.4g%s\n", t.multiplier, t.poses, t.residual_std_mps2,
                   t.multiplier == r.detection.threshold_multiplier ? "  <- chosen" : "");
  }
  const StaticDetection& d = r.detection;
  std::fprintf(out, "static detector: init variance norm %.4g (m/s^2)^2, threshold %.4g (x%.0f); %zu poses\n",
               d.window_variance_init, d.threshold, d.threshold_multiplier, d.poses.size());
  std::fprintf(out, "  %4s %10s %10s %8s %10s %10s %10s %12s %12s\n", "pose", "t_begin[s]", "t_end[s]", "samples",
               "f_x", "f_y", "f_z", "|f|-g before", "after");
  for (size_t k = 0; k < d.poses.size(); ++k) {
    const Pose& p = d.poses[k];
    std::fprintf(out, "  %4zu %10.3f %10.3f %8zu %10.5f %10.5f %10.5f %12.5f", k + 1, p.t_begin_s, p.t_end_s,
                 p.samples(), p.f_mean_mps2.x(), p.f_mean_mps2.y(), p.f_mean_mps2.z(),
                 r.gravity_residual_before_mps2[k]);
    if (k < r.gravity_residual_after_mps2.size()) std::fprintf(out, " %12.3g", r.gravity_residual_after_mps2[k]);
    std::fprintf(out, "\n");
  }
  print_adjustment(out, r.accel);
  if (r.accel.solved)
    std::fprintf(out, "gravity magnitude residual over the poses: rms %.4g m/s^2 before, %.4g m/s^2 after\n",
                 rms(r.gravity_residual_before_mps2), rms(r.gravity_residual_after_mps2));
  print_adjustment(out, r.gyro_earth_rate);
  if (!r.clipped_transitions.empty()) {
    std::fprintf(out, "\ntransitions left out of the gyro rotation fit (gyro output clipped at full scale):");
    for (size_t k : r.clipped_transitions) std::fprintf(out, " %zu->%zu", k + 1, k + 2);
    std::fprintf(out, "\n");
  }
  print_adjustment(out, r.gyro_rotation);
  if (!r.rotation_residual_rad.empty())
    std::fprintf(out, "gravity direction after integrating the calibrated gyro: rms %.4g deg over %zu transitions\n",
                 rms(r.rotation_residual_rad) * kRadToDeg, r.rotation_residual_rad.size());
  std::fprintf(out, "\ngyro method used: %s\n", to_string(r.gyro_method_used));
}

void write_json(const std::string& path, const StaticCalibrationResult& r, const ImuLog& log) {
  std::ofstream f(path);
  if (!f) throw InputError(path, 0, "cannot open for writing");
  f << "{\"source\": " << Json::str(log.source) << ", \"samples\": " << log.size() << ", \"dt_s\": "
    << Json::num(log.dt_s) << ", \"gravity_mps2\": " << Json::num(r.gravity_mps2) << ",\n \"detector\": {\"threshold\": "
    << Json::num(r.detection.threshold) << ", \"threshold_multiplier\": " << Json::num(r.detection.threshold_multiplier)
    << ", \"poses\": [";
  for (size_t k = 0; k < r.detection.poses.size(); ++k) {
    const Pose& p = r.detection.poses[k];
    f << (k ? ", " : "") << "{\"t_begin_s\": " << Json::num(p.t_begin_s) << ", \"t_end_s\": " << Json::num(p.t_end_s)
      << ", \"samples\": " << p.samples() << ", \"f_mean_mps2\": " << Json::arr(p.f_mean_mps2)
      << ", \"w_mean_rad_s\": " << Json::arr(p.w_mean_rad_s) << "}";
  }
  f << "]},\n \"gravity_residual_before_mps2\": " << Json::arr(r.gravity_residual_before_mps2)
    << ",\n \"gravity_residual_after_mps2\": " << Json::arr(r.gravity_residual_after_mps2)
    << ",\n \"rotation_residual_rad\": " << Json::arr(r.rotation_residual_rad)
    << ",\n \"clipped_transitions_from_pose\": " << Json::arr(std::vector<double>(r.clipped_transitions.begin(), r.clipped_transitions.end()))
    << ",\n \"accel\": " << json_adjustment(r.accel) << ",\n \"gyro_earth_rate\": " << json_adjustment(r.gyro_earth_rate)
    << ",\n \"gyro_rotation\": " << json_adjustment(r.gyro_rotation)
    << ",\n \"gyro_method_used\": " << Json::str(to_string(r.gyro_method_used))
    << ",\n \"calibration\": {\"accel\": " << json_triad(r.calibration.accel, "mps2")
    << ", \"gyro\": " << json_triad(r.calibration.gyro, "rad_s") << "}}\n";
  close_checked(f, path);
}

std::vector<std::string> write_sweep_plots(const std::string& prefix, const StaticCalibrationResult& r) {
  std::vector<std::string> made;
  const std::pair<const Adjustment*, const char*> all[] = {
      {&r.accel, "accel"}, {&r.gyro_earth_rate, "gyro_earth_rate"}, {&r.gyro_rotation, "gyro_rotation"}};
  for (const auto& [a, tag] : all) {
    if (!a->solved || a->sweep.points.empty()) continue;
    const std::string base = prefix + "_" + tag + "_ev_sweep";
    {
      std::ofstream dat(base + ".dat");
      dat << "# EV  max_cov_eigenvalue  rms_residual[" << a->residual_unit << " SI]  sigma0  mse\n";
      for (const DampingPoint& p : a->sweep.points)
        dat << p.ev << " " << p.max_cov_eigenvalue << " " << p.rms_misclosure << " " << p.sigma0 << " " << p.mse << "\n";
      close_checked(dat, base + ".dat");
    }
    {
      std::ofstream gp(base + ".gp");
      gp << "set terminal pngcairo size 900,560 noenhanced\nset output " << plot::gnuplot_literal(base + ".png") << "\n"
         << "set title 'Damping sweep, " << tag << ": chosen EV = " << a->ev << "'\n"
         << "set xlabel 'EV (damping added to the standardised normal matrix)'\nset logscale y\n"
         << "set ylabel 'max eigenvalue of the standardised covariance'\nset y2label 'rms residual'\n"
         << "set logscale y2\nset ytics nomirror\nset y2tics\nset key top center\nset grid\n"
         << "set arrow from " << a->ev << ", graph 0 to " << a->ev << ", graph 1 nohead dt 2\n"
         << "plot " << plot::gnuplot_literal(base + ".dat") << " u 1:2 w lp t 'max covariance eigenvalue' axes x1y1, "
         << "'' u 1:3 w lp t 'rms residual' axes x1y2\n";
      close_checked(gp, base + ".gp");
    }
    if (plot::run_gnuplot(base + ".gp", ".") == 0)
      made.push_back(base + ".png");
    else
      spdlog::warn("gnuplot failed on {}.gp (data and script are there to rerun)", base);
  }
  return made;
}

}  // namespace ldv::calib
