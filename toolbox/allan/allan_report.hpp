#pragma once
// The outputs of `ldv allan`: a table per channel in the paper's units (its Tables 4-9 layout), a
// JSON file in SI units, and the KF-GINS `imunoise` block for `ldv nav`.
#include <cstdio>
#include <string>
#include <vector>

#include "toolbox/allan/analysis.hpp"

namespace ldv::allan {

void print_tables(std::FILE* out, const std::vector<ChannelResult>& results);

// JSON layout: see toolbox/allan/README.md. Throws std::runtime_error when the file cannot be written.
void write_json(const std::string& path, const std::string& input, const std::vector<ChannelResult>& results,
                const AnalysisOptions& opt);

// KF-GINS imunoise YAML (arw, vrw, gbstd, abstd, corrtime) from channels named gyro_* / accel_*
// or with rad/s, m/s^2 units; empty when there are none.
std::string kfgins_noise_yaml(const std::vector<ChannelResult>& results);

// The bias instability as a Gauss-Markov process for a filter: sigma and time constant. From the
// fitted GM term when modelled; from the flat B otherwise (the GM whose Allan-deviation peak,
// 0.6174 sigma at 1.893 T, equals the flat floor 0.6643 B at B_tau_s).
struct BiasProcess {
  double sigma = 0.0, time_constant_s = 0.0;
};
BiasProcess bias_process(const NoiseFit& fit);

}  // namespace ldv::allan
