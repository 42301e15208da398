#include "toolbox/assess/outage_table.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "toolbox/assess/json_text.hpp"

namespace ldv::assess {

EnvelopeCheck envelope_check(const OutageResult& r) {
  EnvelopeCheck e;
  const NavDifference& d = r.end_drift;
  for (int i = 0; i < 3; ++i) {
    e.pos[i] = std::abs(d.pos_ned_m(i)) <= 3.0 * r.end_std.pos_ned_m(i);
    e.vel[i] = std::abs(d.vel_ned_mps(i)) <= 3.0 * r.end_std.vel_n_mps(i);
    e.att[i] = std::abs(d.att_phi_n_rad(i)) <= 3.0 * r.end_std.att_rad(i);
  }
  return e;
}

std::vector<OutageLengthSummary> summarise_outages(const OutageRun& run) {
  std::map<double, std::vector<const OutageResult*>> by_length;
  for (const OutageResult& r : run.outages) by_length[r.window.length_s].push_back(&r);
  std::vector<OutageLengthSummary> out;
  for (const auto& [length, rs] : by_length) {
    OutageLengthSummary s;
    s.length_s = length;
    s.outages = static_cast<int>(rs.size());
    int pos_in = 0, vel_in = 0, att_in = 0;
    for (const OutageResult* r : rs) {
      const auto c = table_components(r->end_drift);
      for (int i = 0; i < kComponents; ++i) {
        s.mean_abs_end[i] += std::abs(c[i]) / s.outages;
        s.max_abs_end[i] = std::max(s.max_abs_end[i], std::abs(c[i]));
        s.rms_max_abs[i] += r->max_abs[i] * r->max_abs[i] / s.outages;
      }
      const double h = r->end_drift.pos_ned_m.head<2>().norm();
      s.mean_horizontal_end_m += h / s.outages;
      s.max_horizontal_end_m = std::max(s.max_horizontal_end_m, h);
      s.rms_max_horizontal_m += r->max_horizontal_m * r->max_horizontal_m / s.outages;
      s.mean_3sigma_horizontal_m += 3.0 * r->end_std.pos_ned_m.head<2>().norm() / s.outages;
      const EnvelopeCheck e = envelope_check(*r);
      for (int i = 0; i < 3; ++i) pos_in += e.pos[i], vel_in += e.vel[i], att_in += e.att[i];
    }
    for (double& v : s.rms_max_abs) v = std::sqrt(v);
    s.rms_max_horizontal_m = std::sqrt(s.rms_max_horizontal_m);
    s.inside_3sigma_pos = pos_in / (3.0 * s.outages);
    s.inside_3sigma_vel = vel_in / (3.0 * s.outages);
    s.inside_3sigma_att = att_in / (3.0 * s.outages);
    out.push_back(s);
  }
  return out;
}

void print_outage_table(std::FILE* out, const OutageRun& run, const std::vector<OutageLengthSummary>& summary) {
  std::fprintf(out, "Drift at the end of GNSS outages against the %s (paper Table 12 layout; |drift|, mean and max over the outages)\n",
               run.reference.c_str());
  std::fprintf(out, "%8s %3s %5s | %8s %8s %8s %8s | %7s %7s %7s | %7s %7s %7s\n", "outage", "n", "", "E [m]", "N [m]",
               "D [m]", "hor [m]", "vE m/s", "vN m/s", "vD m/s", "roll", "pitch", "yaw[deg]");
  for (const OutageLengthSummary& s : summary) {
    for (int row = 0; row < 2; ++row) {
      const auto& v = row == 0 ? s.mean_abs_end : s.max_abs_end;
      const double h = row == 0 ? s.mean_horizontal_end_m : s.max_horizontal_end_m;
      std::fprintf(out, "%6.0f s %3d %5s | %8.3f %8.3f %8.3f %8.3f | %7.3f %7.3f %7.3f | %7.4f %7.4f %7.4f\n", s.length_s,
                   s.outages, row == 0 ? "mean" : "max", v[0], v[1], v[2], h, v[3], v[4], v[5], v[6], v[7], v[8]);
    }
  }
  std::fprintf(out, "\nKF-GINS benchmark metric: RMS over the outages of the maximum drift within each outage\n");
  std::fprintf(out, "%8s | %10s %8s %8s | %8s %8s %8s\n", "outage", "hor [m]", "D [m]", "|v|max", "roll", "pitch", "yaw[deg]");
  for (const OutageLengthSummary& s : summary) {
    const auto& r = s.rms_max_abs;
    std::fprintf(out, "%6.0f s | %10.3f %8.3f %8.3f | %8.4f %8.4f %8.4f\n", s.length_s, s.rms_max_horizontal_m, r[2],
                 std::max({r[3], r[4], r[5]}), r[6], r[7], r[8]);
  }
  std::fprintf(out, "\nFilter 3-sigma envelope at the outage end: share of N/E/D components inside\n");
  std::fprintf(out, "%8s | %10s %8s %8s | %14s\n", "outage", "position", "velocity", "attitude", "3sigma hor [m]");
  for (const OutageLengthSummary& s : summary)
    std::fprintf(out, "%6.0f s | %9.0f%% %7.0f%% %7.0f%% | %14.3f\n", s.length_s, 100 * s.inside_3sigma_pos,
                 100 * s.inside_3sigma_vel, 100 * s.inside_3sigma_att, s.mean_3sigma_horizontal_m);
  print_smoothed_table(out, run, summary);
}

void print_smoothed_table(std::FILE* out, const OutageRun& run, const std::vector<OutageLengthSummary>& summary) {
  if (std::none_of(run.outages.begin(), run.outages.end(), [](const OutageResult& r) { return r.smoothed.has_value(); }))
    return;
  std::fprintf(out,
               "\nSmoothed (forward + RTS backward, every gap of a length cut in one run): largest horizontal error "
               "inside each gap against the %s, mean and max over the gaps, beside the forward drift at the gap's end\n",
               run.reference.c_str());
  std::fprintf(out, "%8s %3s | %12s %12s | %15s | %8s | %14s\n", "outage", "n", "smoothed [m]", "max [m]",
               "forward end [m]", "ratio", "smoothed 1sig");
  for (const OutageLengthSummary& s : summary) {
    double sum = 0, mx = 0, fwd = 0, sig = 0;
    int n = 0;
    for (const OutageResult& r : run.outages)
      if (r.window.length_s == s.length_s && r.smoothed) {
        sum += r.smoothed->max_horizontal_m;
        mx = std::max(mx, r.smoothed->max_horizontal_m);
        fwd += r.end_drift.pos_ned_m.head<2>().norm();
        sig += r.smoothed->std_horizontal_at_max_m;
        ++n;
      }
    if (n == 0) continue;
    std::fprintf(out, "%6.0f s %3d | %12.3f %12.3f | %15.3f | %8.3f | %12.3f m\n", s.length_s, n, sum / n, mx, fwd / n,
                 fwd > 0 ? sum / fwd : 0.0, sig / n);
  }
}

namespace {
std::string vec_json(const Vec3& v, double scale = 1.0) { return json_array({v(0) * scale, v(1) * scale, v(2) * scale}); }

std::string difference_json(const NavDifference& d) {
  return JsonObject()
      .add_raw("pos_ned_m", vec_json(d.pos_ned_m))
      .add_raw("vel_ned_mps", vec_json(d.vel_ned_mps))
      .add_raw("rpy_deg", vec_json(d.rpy_rad, kRadToDeg))
      .add_raw("att_phi_ned_deg", vec_json(d.att_phi_n_rad, kRadToDeg))
      .str();
}
}  // namespace

std::string outage_json(const OutageRun& run, const std::vector<OutageLengthSummary>& summary) {
  JsonObject o;
  o.add("tool", "ldv outage").add("schema_version", 1).add("reference", run.reference);
  o.add("imu_samples", run.imu_samples).add("threads", run.threads);
  o.add("uncut_run_s", run.uncut_run_s).add("outages_run_s", run.outages_run_s);
  std::string comps = "[";
  for (int i = 0; i < kComponents; ++i) comps += (i ? "," : "") + json_string(std::string(kComponentNames[i]) + " [" + kComponentUnits[i] + "]");
  o.add_raw("components", comps + "]");
  std::string lengths = "[";
  for (size_t k = 0; k < summary.size(); ++k) {
    const OutageLengthSummary& s = summary[k];
    lengths += (k ? "," : "") + JsonObject()
                                    .add("length_s", s.length_s)
                                    .add("outages", s.outages)
                                    .add_raw("mean_abs_end", json_array({s.mean_abs_end.begin(), s.mean_abs_end.end()}))
                                    .add_raw("max_abs_end", json_array({s.max_abs_end.begin(), s.max_abs_end.end()}))
                                    .add("mean_horizontal_end_m", s.mean_horizontal_end_m)
                                    .add("max_horizontal_end_m", s.max_horizontal_end_m)
                                    .add("rms_max_horizontal_m", s.rms_max_horizontal_m)
                                    .add_raw("rms_max_abs", json_array({s.rms_max_abs.begin(), s.rms_max_abs.end()}))
                                    .add("inside_3sigma_pos", s.inside_3sigma_pos)
                                    .add("inside_3sigma_vel", s.inside_3sigma_vel)
                                    .add("inside_3sigma_att", s.inside_3sigma_att)
                                    .add("mean_3sigma_horizontal_m", s.mean_3sigma_horizontal_m)
                                    .str();
  }
  o.add_raw("lengths", lengths + "]");
  std::string outs = "[";
  for (size_t k = 0; k < run.outages.size(); ++k) {
    const OutageResult& r = run.outages[k];
    JsonObject j;
    j.add("length_s", r.window.length_s).add("start_sow_s", r.window.start_s).add("manoeuvre", r.window.manoeuvre);
    j.add("end_sow_s", r.t_end_s).add_raw("end_drift", difference_json(r.end_drift));
    j.add_raw("end_std", JsonObject()
                             .add_raw("pos_ned_m", vec_json(r.end_std.pos_ned_m))
                             .add_raw("vel_ned_mps", vec_json(r.end_std.vel_n_mps))
                             .add_raw("att_phi_ned_deg", vec_json(r.end_std.att_rad, kRadToDeg))
                             .str());
    j.add("max_horizontal_m", r.max_horizontal_m).add_raw("max_abs", json_array({r.max_abs.begin(), r.max_abs.end()}));
    if (r.uncut_error) j.add_raw("uncut_error", difference_json(*r.uncut_error));
    if (r.smoothed)
      j.add_raw("smoothed", JsonObject()
                                .add("max_horizontal_m", r.smoothed->max_horizontal_m)
                                .add("t_max_sow_s", r.smoothed->t_max_s)
                                .add("std_horizontal_at_max_m", r.smoothed->std_horizontal_at_max_m)
                                .add("max_vertical_m", r.smoothed->max_vertical_m)
                                .add("forward_max_horizontal_m", r.smoothed->forward_max_horizontal_m)
                                .add("samples", r.smoothed->samples)
                                .str());
    std::vector<double> ct, cn, ce, cd, sn, se, sd, yaw;
    for (const DriftPoint& p : r.curve) {
      ct.push_back(p.t_since_start_s);
      cn.push_back(p.pos_ned_m(0)), ce.push_back(p.pos_ned_m(1)), cd.push_back(p.pos_ned_m(2));
      sn.push_back(p.pos_std_ned_m(0)), se.push_back(p.pos_std_ned_m(1)), sd.push_back(p.pos_std_ned_m(2));
      yaw.push_back(p.yaw_deg);
    }
    j.add_raw("curve", JsonObject()
                           .add_raw("t_s", json_array(ct))
                           .add_raw("north_m", json_array(cn))
                           .add_raw("east_m", json_array(ce))
                           .add_raw("down_m", json_array(cd))
                           .add_raw("std_north_m", json_array(sn))
                           .add_raw("std_east_m", json_array(se))
                           .add_raw("std_down_m", json_array(sd))
                           .add_raw("yaw_deg", json_array(yaw))
                           .str());
    outs += (k ? ",\n" : "\n") + j.str();
  }
  o.add_raw("outages", outs + "]");
  return o.str() + "\n";
}

}  // namespace ldv::assess
