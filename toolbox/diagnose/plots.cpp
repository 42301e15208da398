#include "toolbox/diagnose/plots.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "common/io/input_error.hpp"
#include "common/io/output_file.hpp"
#include "common/plot/gnuplot.hpp"

namespace ldv::diag {
namespace {
namespace fs = std::filesystem;

// Segment colours shared by every plot: static, straight, turning, accelerating, outage.
const char* kSegmentColour[kSegmentCount] = {"#999999", "#66bb66", "#ee8833", "#4488ee", "#dd3333"};

std::ofstream open(const fs::path& p) {
  std::ofstream f(p);
  if (!f) throw InputError(p.string(), 0, "cannot open for writing");
  return f;
}

// Writes t, segment code, N E D innovation, N E D sqrt(S_ii), NIS for one kind of measurement.
void write_innovations(const fs::path& p, const FilterRun& run, const std::vector<Segment>& labels,
                       est::SensorName kind) {
  std::ofstream f = open(p);
  f << "# t_s segment innov_n innov_e innov_d sqrtS_n sqrtS_e sqrtS_d nis speed_mps yaw_deg yaw_rate_dps f_h_mps2\n";
  for (const SensitivityRecord& r : run.records) {
    if (r.sensor != kind) continue;
    auto it = std::upper_bound(run.epochs.begin(), run.epochs.end(), r.t_s + 1e-6,
                               [](double t, const EpochSample& e) { return t < e.t_s; });
    const size_t i = it == run.epochs.begin() ? 0 : static_cast<size_t>(it - run.epochs.begin()) - 1;
    const EpochSample& e = run.epochs[i];
    const Vec3 sd = r.S.diagonal().cwiseSqrt();
    f << r.t_s << " " << static_cast<int>(labels[i]) << " " << r.innovation.transpose() << " " << sd.transpose() << " "
      << r.nis << " " << e.v_n_mps.head<2>().norm() << " " << e.rpy_rad.z() * kRadToDeg << " "
      << yaw_rate_rad_s(e) * kRadToDeg << " " << e.f_b_mps2.head<2>().norm() << "\n";
  }
  close_checked(f, p.string());
}

std::string segment_shading(const std::string& dat, double t0) {
  // One filled band per segment kind behind the data (columns: t, segment).
  std::string s;
  for (int k = 0; k < kSegmentCount; ++k)
    s += "'" + dat + "' using ($1-" + std::to_string(t0) + "):($2==" + std::to_string(k) + "?-Y:NaN):($2==" +
         std::to_string(k) + "?Y:NaN) with filledcurves fc rgb '" + kSegmentColour[k] + "' fs transparent solid 0.18 noborder title '" +
         segment_name(static_cast<Segment>(k)) + "', ";
  return s;
}

int run_gnuplot(const fs::path& dir, const std::string& script) { return plot::run_gnuplot(script, dir) == 0 ? 1 : 0; }

}  // namespace

int write_plots(const Diagnosis& d, const std::string& dir_name) {
  const fs::path dir(dir_name);
  fs::create_directories(dir);
  const double t0 = d.before.epochs.empty() ? 0.0 : d.before.epochs.front().t_s;
  write_innovations(dir / "innov_pos_before.dat", d.before, d.labels_before, est::sensors::kGnssPosition);
  write_innovations(dir / "innov_pos_after.dat", d.after, d.labels_after, est::sensors::kGnssPosition);
  int written = 0;
  const std::string term = "set terminal pngcairo size 1400,900 font ',10'\n";
  // The model name comes from the user: inside the titles' literals, as a literal's inner text.
  const std::string quoted_model = plot::gnuplot_label(d.model);
  const std::string model_text = quoted_model.substr(1, quoted_model.size() - 2);

  {  // 1. innovations with their 3-sigma envelope, shaded by manoeuvre
    std::ofstream gp = open(dir / "innovations.gp");
    gp << term << "set output 'innovations.png'\nset multiplot layout 3,1 title 'GNSS position innovations (predicted - measured) "
       << "with 3-sigma envelope, model " << model_text << "'\nset grid\nY = 0\n";
    const char* axis[3] = {"north", "east", "down"};
    for (int a = 0; a < 3; ++a) {
      const std::string c = std::to_string(3 + a), sc = std::to_string(6 + a);
      gp << "stats 'innov_pos_before.dat' using (3*$" << sc << ") nooutput\nY = STATS_max * 1.5\nset yrange [-Y:Y]\n"
         << "set ylabel '" << axis[a] << " [m]'\n" << (a == 2 ? "set xlabel 'time since start [s]'\n" : "")
         << "plot " << segment_shading("innov_pos_before.dat", t0) << "'innov_pos_before.dat' using ($1-" << t0 << "):"
         << c << " with points pt 7 ps 0.3 lc rgb 'black' title 'innovation', '' using ($1-" << t0 << "):(3*$" << sc
         << ") with lines lc rgb 'red' title '+-3 sigma', '' using ($1-" << t0 << "):(-3*$" << sc
         << ") with lines lc rgb 'red' notitle\n";
    }
    gp << "unset multiplot\n";
    close_checked(gp, (dir / "innovations.gp").string());
    written += run_gnuplot(dir, "innovations.gp");
  }
  {  // 2. residual against speed / heading / yaw rate / specific force
    std::ofstream gp = open(dir / "residual_vs_motion.gp");
    gp << term << "set output 'residual_vs_motion.png'\nset multiplot layout 2,2 title 'Horizontal position innovation "
       << "against the motion (a missing effect shows as a pattern)'\nset grid\nset ylabel 'horizontal innovation [m]'\n";
    const char* xs[4][2] = {{"10", "speed [m/s]"}, {"11", "heading [deg]"}, {"12", "yaw rate [deg/s]"},
                            {"13", "horizontal specific force [m/s^2]"}};
    for (auto& x : xs)
      gp << "set xlabel '" << x[1] << "'\nplot 'innov_pos_before.dat' using " << x[0]
         << ":(sqrt($3**2+$4**2)) with points pt 7 ps 0.3 title 'before', 'innov_pos_after.dat' using " << x[0]
         << ":(sqrt($3**2+$4**2)) with points pt 7 ps 0.3 title 'after'\n";
    gp << "unset multiplot\n";
    close_checked(gp, (dir / "residual_vs_motion.gp").string());
    written += run_gnuplot(dir, "residual_vs_motion.gp");
  }
  {  // 3. candidate scores against the threshold
    const ScreeningResult& s = d.steps.front().screening;
    std::ofstream f = open(dir / "scores.dat");
    f << "# index effect statistic p_value\n";
    int i = 0;
    for (const CandidateScore& c : s.ranked)
      f << i++ << " " << c.name << " " << (c.testable ? std::max(c.statistic, 1e-3) : 1e-3) << " " << c.p_value << "\n";
    close_checked(f, (dir / "scores.dat").string());
    std::ofstream gp = open(dir / "scores.gp");
    gp << term << "set output 'scores.png'\nset title 'Screening: robust score statistic per candidate (first pass), "
       << "* = significant (p < " << s.threshold_p << ")'\nset logscale y\nset style fill solid 0.6\nset boxwidth 0.7\n"
       << "set xtics rotate by -30\nset ylabel 'statistic g^T V^-1 g'\nset grid ytics\n"
       << "plot 'scores.dat' using 1:3:xtic(2) with boxes lc rgb '#4488ee' notitle, '' using 1:($4<" << s.threshold_p
       << "?$3*1.3:NaN):(\"*\") with labels notitle\n";
    close_checked(gp, (dir / "scores.gp").string());
    written += run_gnuplot(dir, "scores.gp");
  }
  {  // 4. before / after: NIS, and the error against truth when known
    if (d.truth_before.available) {
      std::ofstream f = open(dir / "truth_error.dat");
      f << "# t_s horizontal_before_m vertical_before_m horizontal_after_m vertical_after_m\n";
      const TruthError &b = d.truth_before, &a = d.truth_after;
      for (size_t i = 0; i < b.t_s.size() && i < a.t_s.size(); ++i)
        f << b.t_s[i] - t0 << " " << b.pos_err_ned_m[i].head<2>().norm() << " " << std::abs(b.pos_err_ned_m[i].z()) << " "
          << a.pos_err_ned_m[i].head<2>().norm() << " " << std::abs(a.pos_err_ned_m[i].z()) << "\n";
      close_checked(f, (dir / "truth_error.dat").string());
    }
    std::ofstream gp = open(dir / "before_after.gp");
    gp << term << "set output 'before_after.png'\nset multiplot layout " << (d.truth_before.available ? 2 : 1)
       << ",1 title 'Before / after adding the verdict'\nset grid\nset logscale y\nset ylabel 'position NIS (3 dof)'\n"
       << "plot 'innov_pos_before.dat' using ($1-" << t0 << "):9 with lines lc rgb '#dd3333' title 'before (" << model_text
       << ")', 'innov_pos_after.dat' using ($1-" << t0 << "):9 with lines lc rgb '#228822' title 'after', 3 with lines dt 2 lc rgb 'black' title 'expected 3'\n";
    if (d.truth_before.available)
      gp << "set ylabel 'position error vs truth [m]'\nset xlabel 'time since start [s]'\nplot 'truth_error.dat' using 1:2 with lines "
         << "lc rgb '#dd3333' title 'horizontal before', '' using 1:4 with lines lc rgb '#228822' title 'horizontal after', "
         << "'' using 1:3 with lines dt 2 lc rgb '#dd3333' title 'vertical before', '' using 1:5 with lines dt 2 lc rgb '#228822' title 'vertical after'\n";
    gp << "unset multiplot\n";
    close_checked(gp, (dir / "before_after.gp").string());
    written += run_gnuplot(dir, "before_after.gp");
  }
  return written;
}

}  // namespace ldv::diag
