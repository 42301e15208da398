#include "tools/ldv/nav_outputs.hpp"

#include <cmath>

#include "common/io/text_table.hpp"
#include "common/logging.hpp"
#include "estimator/filter/nav_filter.hpp"

namespace ldv::cli {
namespace {

std::string std_header(const est::StateLayout& layout) {
  std::string h =
      "# week sow std_pos_n std_pos_e std_pos_d [m] std_vel_n std_vel_e std_vel_d [m/s] std_roll std_pitch std_yaw "
      "[deg]";
  for (const auto& b : layout.blocks())
    for (const auto& n : b.effect->state_names()) h += std::string(" ") + n + "[" + b.effect->print_unit().unit + "]";
  return h + " (each effect state: estimate then std)\n";
}

// One std row: navigation std (position, velocity [m, m/s], attitude [deg]), then each effect's estimate and std.
void std_row(TextOut& out, int week, double t_s, const Eigen::Ref<const Eigen::VectorXd>& nav_std,
             const est::StateLayout& layout, const Eigen::VectorXd& x_eff, const Eigen::VectorXd& eff_std) {
  out.num(week, 0);
  out.num(t_s, 4);
  for (int i = 0; i < 6; ++i) out.num(nav_std(i), 5);
  for (int i = 6; i < 9; ++i) out.num(nav_std(i) * kRadToDeg, 6);
  for (const auto& b : layout.blocks()) {
    const double k = b.effect->print_unit().scale;
    for (int j = 0; j < b.dim; ++j) {
      out.num(x_eff(b.offset - est::kNavDim + j) * k, 6);
      out.num(eff_std(b.offset - est::kNavDim + j) * k, 6);
    }
  }
  out.end_line();
}

}  // namespace

TextOut::TextOut(const std::string& path, const std::string& header) : f_(path) {
  buf_.resize(1 << 18);
  f_.write(header);
}

TextOut::~TextOut() {
  try {
    flush();
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
  }
}

void TextOut::close() {
  flush();
  f_.close();
}

void TextOut::num(double v, int decimals) {
  if (n_ > line_start_) buf_[n_++] = ' ';
  n_ += format_fixed(buf_.data() + n_, v, decimals);
}

void TextOut::text(const char* s) {
  if (n_ > line_start_) buf_[n_++] = ' ';
  while (*s) buf_[n_++] = *s++;
}

void TextOut::end_line() {
  buf_[n_++] = '\n';
  if (n_ + 16384 > buf_.size()) flush();
  line_start_ = n_;
}

void TextOut::flush() {
  const size_t n = n_;
  n_ = line_start_ = 0;
  f_.write(buf_.data(), n);
}

std::string output_base(const std::string& nav_path) {
  std::string b = nav_path;
  if (b.size() > 4 && b.substr(b.size() - 4) == ".nav") b.resize(b.size() - 4);
  return b;
}

NavRecord nav_record(const est::NavState& s, int week, double t_gnss_s) {
  NavRecord rec;
  rec.week = week;
  rec.sow_s = t_gnss_s;
  rec.pos = s.pos;
  rec.vel_n_mps = s.v_n_mps;
  rec.rpy_rad = s.rpy_rad();
  if (rec.rpy_rad.z() < 0) rec.rpy_rad.z() += 2.0 * kPi;  // KF-GINS prints yaw in [0, 360)
  return rec;
}

NavOutputs::NavOutputs(const std::string& nav_path, const est::NavFilter& f, double std_rate_hz)
    : nav_(nav_path),
      std_(output_base(nav_path) + "_std.txt", std_header(f.layout())),
      innov_(output_base(nav_path) + "_innovations.txt",
             "# t_sow kind innov_1 innov_2 innov_3 sqrtS_11 sqrtS_22 sqrtS_33 nis accepted(1/0) "
             "(innovation = predicted - measured; position NED [m], velocity NED [m/s])\n"),
      std_period_(std_rate_hz > 0 ? 1.0 / std_rate_hz : 0.0) {}

void NavOutputs::epoch(const est::NavFilter& f, int week) {
  const est::NavState& s = f.state();
  // A file's times only increase (issue 46): a time_offset estimate stepping back by more than a sample interval
  // would stamp a row before the one written last; such rows are counted, not written.
  const double t_gnss_s = f.gnss_time_s();
  if (!(t_gnss_s > last_row_t_s_)) {
    ++rows_not_advancing_;
    return;
  }
  last_row_t_s_ = t_gnss_s;
  nav_.write(nav_record(s, week, t_gnss_s));
  if (s.t_s + 1e-9 < next_std_t_) return;
  next_std_t_ = s.t_s + std_period_;
  const est::NavStd nav = f.nav_std();  // the attitude's with the gyros' Q, which no state holds
  est::Vec9 nav_sd;
  nav_sd << nav.pos_ned_m, nav.vel_n_mps, nav.att_rad;
  const Eigen::VectorXd P_diag = f.covariance().diagonal();
  const Eigen::VectorXd eff_sd = P_diag.tail(P_diag.size() - est::kNavDim).cwiseMax(0.0).cwiseSqrt();
  std_row(std_, week, f.gnss_time_s(), nav_sd, f.layout(), f.effect_state(), eff_sd);
}

void NavOutputs::innovation(const est::InnovationRecord& r) {
  innov_.num(r.t_s, 4);
  innov_.text(std::string(r.sensor).c_str());
  // Three columns whatever the sensor's rows (the aids have 1-3; missing ones are written as 0).
  for (int i = 0; i < 3; ++i) innov_.num(i < r.innovation.size() ? r.innovation(i) : 0.0, 5);
  for (int i = 0; i < 3; ++i) innov_.num(i < r.innovation.size() ? std::sqrt(r.S(i, i)) : 0.0, 5);
  innov_.num(r.nis, 3);
  innov_.num(r.used() ? 1 : 0, 0);  // used: an outlier the robust update kept a trace of counts as rejected
  innov_.end_line();
}

void NavOutputs::close() {
  nav_.close();
  std_.close();
  innov_.close();
}

void write_smoothed(const est::SmoothedRun& run, const est::StateLayout& layout, const std::string& nav_path,
                    double std_rate_hz, const Vec3& gyro_quantization_rad, double time_offset_s,
                    const std::function<void(double)>& progress) {
  const std::string base = output_base(nav_path);
  NavWriter nav(nav_path);
  TextOut sd(base + "_std.txt", std_header(layout));
  TextOut sep(base + "_separation.txt",
              std::string(kSeparationHeaderStart) +
                  " [m] sep_vn sep_ve sep_vd [m/s] sep_phi_n sep_phi_e sep_phi_d [deg] "
                  "std_n std_e std_d [m] std_vn std_ve std_vd [m/s] std_phi_n std_phi_e std_phi_d [deg] (separation = "
                  "forward minus smoothed; std = its expected 1-sigma, sqrt(P forward - P smoothed); phi: attitude "
                  "error angles about N E D)\n");
  const double period = std_rate_hz > 0 ? 1.0 / std_rate_hz : 0.0;
  double next_t = -1e300;
  for (std::size_t i = 0; i < run.size(); ++i) {
    const est::SmoothedRow r = run.row(i);
    const double t_gnss_s = r.smoothed.t_s + time_offset_s;
    nav.write(nav_record(r.smoothed, r.week, t_gnss_s));
    if (progress && i % 20000 == 0) progress(static_cast<double>(i) / run.size());
    if (r.smoothed.t_s + 1e-9 < next_t) continue;
    next_t = r.smoothed.t_s + period;
    est::Vec9 nav_sd = r.std_smoothed;
    nav_sd.segment<3>(est::kAtt) =
        (nav_sd.segment<3>(est::kAtt).cwiseAbs2() +
         est::attitude_quantization_cov_n(r.smoothed.C_b_n(), gyro_quantization_rad).diagonal())
            .cwiseSqrt();
    std_row(sd, r.week, t_gnss_s, nav_sd, layout, r.x_eff_smoothed, r.std_eff_smoothed);
    sep.num(r.week, 0);
    sep.num(t_gnss_s, 4);
    for (const est::Vec9* v : {&r.separation, &r.std_separation})
      for (int k = 0; k < 9; ++k) sep.num(k < 6 ? (*v)(k) : (*v)(k)*kRadToDeg, k < 6 ? 5 : 6);
    sep.end_line();
  }
  nav.close();
  sd.close();
  sep.close();
}

}  // namespace ldv::cli
