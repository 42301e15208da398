#pragma once
// The paper's Table 12 from an outage run: per outage length, the mean and maximum over the outages of
// the absolute drift at the end of each outage (E N D [m], vE vN vD [m/s], roll pitch yaw [deg]);
// the KF-GINS benchmark metric (RMS over outages of the maximum drift within each outage); and how
// often the filter's own 3-sigma envelope held the drift.
#include <array>
#include <cstdio>
#include <string>
#include <vector>

#include "toolbox/assess/outage_run.hpp"
#include "toolbox/assess/solution_comparison.hpp"

namespace ldv::assess {

struct OutageLengthSummary {
  double length_s = 0.0;
  int outages = 0;
  std::array<double, kComponents> mean_abs_end{}, max_abs_end{};  // table components, units m, m/s, deg
  double mean_horizontal_end_m = 0.0, max_horizontal_end_m = 0.0;
  // KF-GINS metric: RMS over the outages of each outage's maximum drift.
  double rms_max_horizontal_m = 0.0;
  std::array<double, kComponents> rms_max_abs{};
  // 3-sigma envelope: share of outage-end components with |drift| <= 3 sigma (N E D each).
  double inside_3sigma_pos = 0.0, inside_3sigma_vel = 0.0, inside_3sigma_att = 0.0;
  double mean_3sigma_horizontal_m = 0.0;  // 3 x sqrt(sigma_N^2 + sigma_E^2), mean over the outages
};

std::vector<OutageLengthSummary> summarise_outages(const OutageRun& run);

// Whether each N, E, D component of position / velocity / attitude(phi) is inside 3 sigma.
struct EnvelopeCheck {
  std::array<bool, 3> pos{}, vel{}, att{};
};
EnvelopeCheck envelope_check(const OutageResult& r);

void print_outage_table(std::FILE* out, const OutageRun& run, const std::vector<OutageLengthSummary>& s);
// With smoothed results (ldv outage --smooth): the largest smoothed error inside the gaps per length (also
// printed by print_outage_table).
void print_smoothed_table(std::FILE* out, const OutageRun& run, const std::vector<OutageLengthSummary>& s);
std::string outage_json(const OutageRun& run, const std::vector<OutageLengthSummary>& s);

}  // namespace ldv::assess
