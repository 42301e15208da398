#pragma once
// Units at the edges: input units converted to SI once, and the paper's engineering units for the
// noise terms (Moafipoor et al., Tables 4-9: Q arcsec or m/h, N deg/sqrt(h) or m/s/sqrt(h),
// B deg/h or m/s/h, K deg/h/sqrt(h) or m/s/h/sqrt(h), R deg/h/h or m/s/h^2).
#include <string>

namespace ldv::allan {

enum class Quantity { kAngularRate, kAcceleration, kGeneric };

struct InputUnit {
  std::string name;           // as given, e.g. "deg/s"
  Quantity quantity = Quantity::kGeneric;
  double to_si = 1.0;         // SI value = raw * to_si (rad/s, m/s^2, or the unit itself)
  const char* si_name = "1";  // "rad/s", "m/s^2", "1"
};

// rad/s, deg/s, deg/h, rad/h, m/s^2 (m/s2), g, mg, ug, 1 (si, none). Throws std::invalid_argument
// listing the accepted names.
InputUnit parse_input_unit(const std::string& name);

// Quantity of a channel from its SI unit name ("rad/s" -> angular rate, ...).
Quantity quantity_of_si_unit(const std::string& si_unit);

enum class Term { kQ, kN, kB, kK, kR };
const char* term_name(Term t);  // "Q", "N", ...

// The paper's unit for a term of a channel of that quantity, and the factor from the SI value of
// the term (Q: unit*s, N: unit*s^0.5, B: unit, K: unit/s^0.5, R: unit/s, unit = rad/s or m/s^2).
struct EngineeringUnit {
  const char* name;
  double from_si;
};
EngineeringUnit paper_unit(Quantity q, Term t);

// SI unit of a term's value for a rate in `si_unit` (e.g. "rad/s" -> N in "rad/s/sqrt(Hz)").
std::string si_term_unit(const std::string& si_unit, Term t);

inline constexpr double kStandardGravity = 9.80665;

}  // namespace ldv::allan
