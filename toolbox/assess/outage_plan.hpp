#pragma once
// Where `ldv outage` cuts GNSS: for each length, outages starting during manoeuvres (turning or
// changing speed, seen in the GNSS track itself, so the plan is the same with or without truth),
// after the filter has converged, repeated over the run with recovery time between them.
#include <vector>

#include "common/formats/nav_types.hpp"

namespace ldv::assess {

struct OutagePlanOptions {
  double converge_s = 120.0;         // no outage starts earlier than this after the first fix it is given
  double recovery_s = 120.0;         // GNSS kept between the end of one outage and the next start
  double manoeuvre_accel_mps2 = 0.3; // horizontal acceleration (incl. centripetal) that counts as a manoeuvre
  double min_speed_mps = 1.0;        // moving
  double max_wait_s = 60.0;          // no manoeuvre within this: start at the first moving epoch instead
};

struct OutageWindow {
  double length_s = 0.0;
  double start_s = 0.0;  // epoch of the last fix used; fixes in (start, start + length] are removed
  bool manoeuvre = false;  // started during a manoeuvre (else only moving)
};

// Horizontal acceleration and speed at each fix from the fix positions (+-1 s differences).
struct TrackMotion {
  double t_s, speed_mps, accel_mps2;
};
std::vector<TrackMotion> track_motion(const std::vector<GnssFix>& gnss);

// All windows for all lengths (each length planned over the whole run on its own), sorted by start.
// Outages end no later than t_end_s (the end of the IMU data).
std::vector<OutageWindow> plan_outages(const std::vector<GnssFix>& gnss, const std::vector<double>& lengths_s,
                                       double t_end_s, const OutagePlanOptions& options);

}  // namespace ldv::assess
