#pragma once
// Reading the inputs of `ldv allan` into phase series, one per channel, in SI units.
//  kfgins    : KF-GINS imu.txt increments -> six rates gyro_x..z [rad/s], accel_x..z [m/s^2]
//  csv       : a header line naming the columns, then rows; chosen columns with their units
//  phase     : Stable32-style phase data (one value per line, or "time value"), up to two header lines
//  frequency : the same layout holding fractional frequency (or a rate, with --units)
// Hours of data stream through a chunked reader; memory is one double per sample per channel.
#include <functional>
#include <string>
#include <vector>

#include "toolbox/allan/phase_series.hpp"

namespace ldv::allan {

enum class InputFormat { kKfGins, kCsv, kPhase, kFrequency };
InputFormat parse_input_format(const std::string& name);  // throws std::invalid_argument

struct InputOptions {
  InputFormat format = InputFormat::kCsv;
  double rate_hz = 0.0;                  // sample rate; 0: from --tau0, the time column or the time stamps
  double tau0_s = 0.0;                   // sample interval (alternative to rate_hz)
  std::vector<std::string> columns;      // csv: names or 1-based indices; empty: all but the time column
  std::vector<std::string> units;        // one for all columns or one per column (default "1")
  std::vector<double> counts_per_unit;   // raw counts per unit (one or per column; empty: 1)
  std::string time_column;               // csv: column with time stamps [s] (used for tau0 only)
  double nominal = 0.0;                  // frequency: raw values are absolute (Hz); y = (f - f0) / f0
};

using ProgressFn = std::function<void(const std::string&)>;

// Throws InputError naming file, line and column for malformed input, and for inputs no analysis
// can use (empty, fewer than 8 samples, a constant channel).
std::vector<PhaseSeries> read_allan_input(const std::string& path, const InputOptions& opt,
                                          const ProgressFn& progress = nullptr);

}  // namespace ldv::allan
