#pragma once
// Value checks for ldv's options. CLI11's PositiveNumber and Range let NaN through (every comparison
// with NaN is false), so ldv uses these instead; and every option of every subcommand refuses a number
// that is not finite ("nan", "inf", "1e999"), so no NaN reaches a planner, a filter or a loop bound.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

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

// An option whose number the library checks where it uses it, naming the option (e.g. ldv sim's request
// validation: the same bounds for the command line and for callers of the library). Marked so that
// unbounded_number_options() passes it; the default suite gives each such option 1e12 and -1e12 and requires the
// refusal (tests/hardening/test_cli_numbers.cpp).
inline CLI::Validator checked_where_used() {
  return CLI::Validator([](std::string&) -> std::string { return {}; }, "", "CHECKED_WHERE_USED");
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

// Calls visit(option, "ldv sub") for every option of every command and subcommand.
template <typename Visit>
void for_each_option(const CLI::App& app, const std::string& path, const Visit& visit) {
  for (const CLI::Option* o : app.get_options()) visit(*o, path);
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
    for_each_option(*sub, path + " " + sub->get_name(), visit);
}

// Whether an option carries a validator of this name (CLI11 2.1 answers by throwing).
inline bool has_validator(const CLI::Option& o, const std::string& name) {
  try {
    const_cast<CLI::Option&>(o).get_validator(name);
    return true;
  } catch (const CLI::OptionNotFound&) {
    return false;
  }
}

// Options that take a number but carry no bounds (finite_range, finite_positive, CLI::Range or checked_where_used): a
// number a user can give is checked where it is given (issue 46: `--week 99999999`, `calib static --height-m` reached
// the work unchecked). `ldv help --unbounded-numbers` lists them; the default suite requires the list to be empty.
inline std::vector<std::string> unbounded_number_options(const CLI::App& app) {
  std::vector<std::string> found;
  for_each_option(app, "ldv", [&](const CLI::Option& o, const std::string& path) {
    const std::string type = o.get_type_name();
    const bool takes_number = o.get_type_size() > 0 && (type.rfind("FLOAT", 0) == 0 || type.rfind("INT", 0) == 0 ||
                                                        type.rfind("UINT", 0) == 0 || type.rfind("NUMBER", 0) == 0);
    if (!takes_number) return;
    bool bounded = false;
    for (int i = 0;; ++i) {
      const CLI::Validator* v = nullptr;
      try {
        v = const_cast<CLI::Option&>(o).get_validator(i);
      } catch (const CLI::OptionNotFound&) {
        break;
      }
      // CLI::Range describes itself "TYPE in [lo - hi]" (NaN is refused by refuse_non_finite_numbers)
      bounded |= v->get_name() == "FINITE_RANGE" || v->get_name() == "FINITE_POSITIVE" ||
                 v->get_name() == "CHECKED_WHERE_USED" || v->get_description().find(" in [") != std::string::npos;
    }
    if (!bounded) found.push_back(path + " " + o.get_name());
  });
  return found;
}

// The options marked checked_where_used(), as "ldv sub --option VALUES" (VALUES: how many numbers it expects).
inline std::vector<std::string> checked_where_used_options(const CLI::App& app) {
  std::vector<std::string> found;
  for_each_option(app, "ldv", [&](const CLI::Option& o, const std::string& path) {
    if (has_validator(o, "CHECKED_WHERE_USED"))
      found.push_back(path + " " + o.get_name() + " " + std::to_string(std::max(1, o.get_expected_min())));
  });
  return found;
}

}  // namespace ldv::cli
