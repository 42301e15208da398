#pragma once
// `ldv compare`: the paper's Tables 10-11. Solution A minus solution B (or truth) at A's epochs,
// B interpolated, after a settling time: mean, std and RMS of each component.
#include <array>
#include <string>

#include "toolbox/assess/nav_series.hpp"

namespace ldv::assess {

// Component order of every comparison table: E N D [m], vE vN vD [m/s], roll pitch yaw [deg].
constexpr int kComponents = 9;
extern const std::array<const char*, kComponents> kComponentNames;
extern const std::array<const char*, kComponents> kComponentUnits;

struct NavDifference;
// A difference in the table's components and units (m, m/s, deg).
std::array<double, kComponents> table_components(const NavDifference& d);

struct ComponentStats {
  double mean = 0.0, std = 0.0, rms = 0.0, max_abs = 0.0;
};

struct ComparisonResult {
  long epochs = 0;           // A epochs compared
  long unmatched = 0;        // A epochs after the settling time that B does not cover
  double t_first_s = 0.0, t_last_s = 0.0;
  std::array<ComponentStats, kComponents> stats{};
  // One side has no GPS week (a .nav of KF-GINS or of ldv nav without a week: week 0): matched by seconds of week.
  bool matched_by_seconds_of_week = false;
  std::string matching_note() const;  // "" or what was matched how, in words
};

struct ComparisonOptions {
  double settle_s = 0.0;     // skip A's first seconds (filter convergence)
  double max_gap_s = 1.5;    // do not interpolate B across longer gaps
};

// Throws std::invalid_argument if no epoch can be compared.
ComparisonResult compare_solutions(const NavSeries& a, const NavSeries& b, const ComparisonOptions& options);

void print_comparison(std::FILE* out, const ComparisonResult& r, const std::string& a_name, const std::string& b_name);
std::string comparison_json(const ComparisonResult& r, const std::string& a_name, const std::string& b_name);

}  // namespace ldv::assess
