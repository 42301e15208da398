#include "toolbox/allan/tau_list.hpp"

#include <cmath>
#include <stdexcept>

namespace ldv::allan {

TauSpacing parse_tau_spacing(const std::string& name) {
  if (name == "all") return TauSpacing::kAll;
  if (name == "octave") return TauSpacing::kOctave;
  if (name == "log") return TauSpacing::kLog;
  throw std::invalid_argument("unknown tau spacing '" + name + "' (expected all, octave or log)");
}

std::vector<long> averaging_factors(TauSpacing spacing, long m_max, int per_decade) {
  std::vector<long> ms;
  if (m_max < 1) return ms;
  switch (spacing) {
    case TauSpacing::kAll:
      for (long m = 1; m <= m_max; ++m) ms.push_back(m);
      break;
    case TauSpacing::kOctave:
      for (long m = 1; m <= m_max; m *= 2) ms.push_back(m);
      break;
    case TauSpacing::kLog: {
      if (per_decade < 1) throw std::invalid_argument("points per decade must be >= 1");
      const double decades = std::log10(static_cast<double>(m_max));
      const long steps = static_cast<long>(std::floor(decades * per_decade + 1e-9));
      for (long k = 0; k <= steps; ++k) {
        const long m = std::lround(std::pow(10.0, static_cast<double>(k) / per_decade));
        if (m <= m_max && (ms.empty() || m > ms.back())) ms.push_back(m);
      }
      if (ms.back() != m_max && static_cast<double>(m_max) / ms.back() > std::pow(10.0, 0.5 / per_decade)) {
        ms.push_back(m_max);
      }
      break;
    }
  }
  return ms;
}

}  // namespace ldv::allan
