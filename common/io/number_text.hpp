#pragma once
// A number as messages print it: six significant digits, the way %g (and an ostream's default) shows it.
#include <cstdio>
#include <string>

namespace ldv {

inline std::string six_significant(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", v);
  return text;
}

}  // namespace ldv
