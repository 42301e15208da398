#pragma once
// One channel as the deviations want it: phase x (the integral of the rate) on a uniform grid.
#include <string>
#include <vector>

namespace ldv::allan {

enum class DataKind { kPhase, kFrequency };

struct PhaseSeries {
  std::string name;        // channel name, e.g. "gyro_x"
  std::string unit;        // SI unit of the rate (frequency) quantity, e.g. "rad/s", "m/s^2", "1"
  double tau0_s = 1.0;     // sample interval
  DataKind source = DataKind::kFrequency;  // what the input file held (drives noise identification)
  double mean_rate = 0.0;  // removed mean rate (frequency offset, e.g. the gyro bias), unit
  std::vector<double> x;   // phase, unit * s, N = samples + 1 for frequency input
};

// Turns rates y (in place, no copy) into phase with the mean rate removed: x[0] = 0,
// x[i+1] = x[i] + (y[i] - mean) tau0. Removing the mean changes no deviation (they difference the
// phase at least twice) but keeps x small, so the differences keep their precision over hours.
PhaseSeries phase_from_rates(std::vector<double>&& y, double tau0_s, std::string name, std::string unit);

// Takes phase as given (clock data, PHASE.DAT) and removes the straight line through its end
// points, for the same reason.
PhaseSeries phase_from_phase(std::vector<double>&& x, double tau0_s, std::string name, std::string unit);

}  // namespace ldv::allan
