#pragma once
// Value checks for ldv's options. CLI11's PositiveNumber and Range let NaN through (every comparison
// with NaN is false), so ldv uses these instead; and every option of every subcommand refuses a number
// that is not finite ("nan", "inf", "1e999"), so no NaN reaches a planner, a filter or a loop bound.
#include <CLI/CLI.hpp>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <string>

namespace ldv::cli {

// The number the whole text spells, if it spells one.
inline bool parse_number(const std::string& text, double& value) {
  if (text.empty()) return false;
  char* end = nullptr;
  errno = 0;
  value = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size()) return false;
  if (errno == ERANGE && std::abs(value) > 1.0) value = HUGE_VAL;  // overflow: 1e999
  return true;
}

// A finite number in [lo, hi] (NaN refused).
inline CLI::Validator finite_range(double lo, double hi) {
  return CLI::Validator(
      [lo, hi](std::string& text) -> std::string {
        double v = 0.0;
        if (!parse_number(text, v)) return "'" + text + "' is not a number";
        if (!std::isfinite(v) || v < lo || v > hi)
          return "'" + text + "' is outside [" + CLI::detail::to_string(lo) + ", " + CLI::detail::to_string(hi) + "]";
        return {};
      },
      "in [" + CLI::detail::to_string(lo) + ", " + CLI::detail::to_string(hi) + "]", "FINITE_RANGE");
}

// A finite number > 0 and at most `hi`.
inline CLI::Validator finite_positive(double hi = 1e300) {
  return CLI::Validator(
      [hi](std::string& text) -> std::string {
        double v = 0.0;
        if (!parse_number(text, v)) return "'" + text + "' is not a number";
        if (!std::isfinite(v) || v <= 0.0 || v > hi)
          return "'" + text + "' must be a finite number > 0 and <= " + CLI::detail::to_string(hi);
        return {};
      },
      "POSITIVE", "FINITE_POSITIVE");
}

// Every option, in every subcommand: a value that spells a number must spell a finite one.
inline void refuse_non_finite_numbers(CLI::App& app) {
  const CLI::Validator finite(
      [](std::string& text) -> std::string {
        double v = 0.0;
        if (parse_number(text, v) && !std::isfinite(v)) return "'" + text + "' is not a finite number";
        return {};
      },
      "", "FINITE");
  for (CLI::Option* o : app.get_options()) o->check(finite);
  for (CLI::App* sub : app.get_subcommands({})) refuse_non_finite_numbers(*sub);
}

}  // namespace ldv::cli
