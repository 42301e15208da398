#include "toolbox/assess/solution_comparison.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "toolbox/assess/json_text.hpp"
#include "toolbox/assess/nav_difference.hpp"

namespace ldv::assess {

const std::array<const char*, kComponents> kComponentNames = {"east", "north", "down", "v_east", "v_north",
                                                              "v_down", "roll", "pitch", "yaw"};
const std::array<const char*, kComponents> kComponentUnits = {"m", "m", "m", "m/s", "m/s", "m/s", "deg", "deg", "deg"};

// The paper's order (Tables 10-12): position E N D, velocity E N D.
std::array<double, kComponents> table_components(const NavDifference& d) {
  return {d.pos_ned_m.y(),   d.pos_ned_m.x(),   d.pos_ned_m.z(),   d.vel_ned_mps.y(),         d.vel_ned_mps.x(),
          d.vel_ned_mps.z(), d.rpy_rad.x() * kRadToDeg, d.rpy_rad.y() * kRadToDeg, d.rpy_rad.z() * kRadToDeg};
}

ComparisonResult compare_solutions(const NavSeries& a, const NavSeries& b, const ComparisonOptions& o) {
  ComparisonResult r;
  if (a.empty() || b.empty()) throw std::invalid_argument("compare: an empty solution");
  const double t_settled = a.t_begin_s() + o.settle_s;
  // Matched on GPS time (week and seconds of week) when both know their week: A's t_s in B's time base. Week 0 is
  // "not known" (GPS week 0 is 1980; KF-GINS files carry seconds of week only): then by seconds of week.
  const bool weeks_known = a.week() > 0 && b.week() > 0;
  r.matched_by_seconds_of_week = !weeks_known;
  const double a_to_b_s = weeks_known ? (a.week() - b.week()) * NavSeries::kSecondsPerWeek : 0.0;
  std::array<double, kComponents> sum{}, sum2{};
  for (const NavSample& s : a.samples()) {
    if (s.t_s < t_settled) continue;
    const auto ref = b.at(s.t_s + a_to_b_s, o.max_gap_s);
    if (!ref) {
      ++r.unmatched;
      continue;
    }
    const auto c = table_components(nav_difference(s, *ref));
    for (int i = 0; i < kComponents; ++i) {
      sum[i] += c[i];
      sum2[i] += c[i] * c[i];
      r.stats[i].max_abs = std::max(r.stats[i].max_abs, std::abs(c[i]));
    }
    if (r.epochs == 0) r.t_first_s = s.t_s;
    r.t_last_s = s.t_s;
    ++r.epochs;
  }
  if (r.epochs == 0 && weeks_known && (a.week() != b.week() || a.last_week() != b.last_week()))
    throw std::invalid_argument("compare: the two solutions share no GPS time: the first spans weeks " +
                                std::to_string(a.week()) + ".." + std::to_string(a.last_week()) + ", the second " +
                                std::to_string(b.week()) + ".." + std::to_string(b.last_week()) +
                                " (a .nav written without a known week has week 0: rerun ldv nav with --week)");
  if (r.epochs == 0) throw std::invalid_argument("compare: the two solutions share no epoch after the settling time");
  for (int i = 0; i < kComponents; ++i) {
    ComponentStats& st = r.stats[i];
    st.mean = sum[i] / r.epochs;
    st.rms = std::sqrt(sum2[i] / r.epochs);
    st.std = std::sqrt(std::max(0.0, st.rms * st.rms - st.mean * st.mean));
  }
  return r;
}

std::string ComparisonResult::matching_note() const {
  return matched_by_seconds_of_week ? "matched by seconds of week: a solution without a GPS week (week 0)" : "";
}

void print_comparison(std::FILE* out, const ComparisonResult& r, const std::string& a_name, const std::string& b_name) {
  if (r.matched_by_seconds_of_week) std::fprintf(out, "%s\n", r.matching_note().c_str());
  std::fprintf(out, "%s minus %s: %ld epochs from %.3f to %.3f s (%ld not covered by the second)\n", a_name.c_str(),
               b_name.c_str(), r.epochs, r.t_first_s, r.t_last_s, r.unmatched);
  std::fprintf(out, "%-10s %-5s %12s %12s %12s %12s\n", "component", "unit", "mean", "std", "RMS", "max |d|");
  for (int i = 0; i < kComponents; ++i) {
    const ComponentStats& s = r.stats[i];
    std::fprintf(out, "%-10s %-5s %12.4f %12.4f %12.4f %12.4f\n", kComponentNames[i], kComponentUnits[i], s.mean, s.std,
                 s.rms, s.max_abs);
  }
}

std::string comparison_json(const ComparisonResult& r, const std::string& a_name, const std::string& b_name) {
  JsonObject o;
  o.add("tool", "ldv compare").add("a", a_name).add("b", b_name).add("epochs", r.epochs).add("unmatched", r.unmatched);
  o.add("t_first_s", r.t_first_s).add("t_last_s", r.t_last_s);
  o.add("matched_by_seconds_of_week", r.matched_by_seconds_of_week);
  JsonObject comps;
  for (int i = 0; i < kComponents; ++i) {
    const ComponentStats& s = r.stats[i];
    comps.add_raw(kComponentNames[i], JsonObject()
                                          .add("unit", kComponentUnits[i])
                                          .add("mean", s.mean)
                                          .add("std", s.std)
                                          .add("rms", s.rms)
                                          .add("max_abs", s.max_abs)
                                          .str());
  }
  o.add_raw("components", comps.str());
  return o.str();
}

}  // namespace ldv::assess
