#pragma once
// Log-log plot of the overlapping Allan deviation with its confidence bars, the fitted total and
// every fitted term: writes FILE.png.dat and FILE.png.gp next to the PNG and runs gnuplot.
#include <string>
#include <vector>

#include "toolbox/allan/analysis.hpp"

namespace ldv::allan {

// Throws std::runtime_error when gnuplot fails (the .gp and .dat files stay for inspection).
void plot_allan(const std::string& png_path, const std::vector<ChannelResult>& results);

}  // namespace ldv::allan
