#pragma once
// Averaging factors m (tau = m tau0) at which to evaluate a deviation.
#include <string>
#include <vector>

namespace ldv::allan {

enum class TauSpacing { kAll, kOctave, kLog };
TauSpacing parse_tau_spacing(const std::string& name);  // "all" | "octave" | "log"; throws std::invalid_argument

// m from 1 up to m_max (inclusive): every integer, powers of two, or `per_decade` log-spaced values
// rounded to distinct integers. The default upper limit for analysis is N/4 (see max_factor_for).
std::vector<long> averaging_factors(TauSpacing spacing, long m_max, int per_decade = 10);

// N/4 phase points, the usual limit where an overlapped estimate still has a few degrees of freedom.
inline long default_max_factor(long n_phase) { return n_phase / 4; }

}  // namespace ldv::allan
