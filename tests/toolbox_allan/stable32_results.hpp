#pragma once
// Reader for Stable32 result tables (columns: AF Tau #N Alpha MinSigma Sigma MaxSigma) and the
// printed-digits comparison the reference values call for.
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace ldv::allan::test {

struct Stable32Row {
  long af = 0;
  double tau = 0, min_sigma = 0, sigma = 0, max_sigma = 0;
  long n = 0;
  int alpha = 0;
};

inline std::string shared_data(const std::string& rel) { return std::string(LDV_SHARED_DATA_DIR) + "/" + rel; }

inline std::vector<Stable32Row> read_stable32_table(const std::string& path) {
  std::vector<Stable32Row> rows;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ss(line);
    Stable32Row r;
    if (ss >> r.af >> r.tau >> r.n >> r.alpha >> r.min_sigma >> r.sigma >> r.max_sigma) rows.push_back(r);
  }
  return rows;
}

// True when `value` rounds to `printed` at `digits` significant digits: half a unit of the last
// printed digit, plus 1e-7 relative for values that sit on a rounding edge (the reference tools'
// own arithmetic, e.g. Stable32 scales the OCXO frequencies by the mean, we by the nominal).
inline bool matches_printed(double value, double printed, int digits) {
  if (printed == 0.0) return value == 0.0;
  const double exponent = std::floor(std::log10(std::fabs(printed)));
  const double half_unit = 0.5 * std::pow(10.0, exponent - (digits - 1));
  return std::fabs(value - printed) <= half_unit + 1e-7 * std::fabs(printed);
}

}  // namespace ldv::allan::test
