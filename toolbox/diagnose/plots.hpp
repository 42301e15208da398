#pragma once
// Plots that answer questions (gnuplot, PNG): innovations with their 3-sigma envelope shaded by
// manoeuvre, residual against speed / heading / yaw rate / specific force, candidate scores,
// before/after. Writes the data (.dat) and the script (.gp) beside each PNG, then runs gnuplot.
#include <string>

#include "toolbox/diagnose/diagnosis.hpp"

namespace ldv::diag {
// Returns how many PNGs gnuplot wrote (0 when gnuplot is missing: the data and scripts stay).
int write_plots(const Diagnosis& d, const std::string& dir);
}
