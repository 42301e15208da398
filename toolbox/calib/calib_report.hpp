#pragma once
// What `ldv calib static` shows: the human-readable report, the JSON document and the EV-sweep plot.
#include <cstdio>
#include <string>
#include <vector>

#include "toolbox/calib/static_calibration.hpp"

namespace ldv::calib {

void print_report(std::FILE* out, const StaticCalibrationResult& r, const ImuLog& log);
void write_json(const std::string& path, const StaticCalibrationResult& r, const ImuLog& log);
// Writes PREFIX_ev_sweep.dat and .gp and runs gnuplot to PREFIX_ev_sweep.png; returns the PNG paths made.
std::vector<std::string> write_sweep_plots(const std::string& prefix, const StaticCalibrationResult& r);

}  // namespace ldv::calib
