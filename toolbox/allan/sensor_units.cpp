#include "toolbox/allan/sensor_units.hpp"

#include <cmath>
#include <stdexcept>

namespace ldv::allan {
namespace {
constexpr double kDeg = M_PI / 180.0;
constexpr double kHour = 3600.0;
}  // namespace

InputUnit parse_input_unit(const std::string& name) {
  if (name == "rad/s") return {name, Quantity::kAngularRate, 1.0, "rad/s"};
  if (name == "deg/s") return {name, Quantity::kAngularRate, kDeg, "rad/s"};
  if (name == "deg/h") return {name, Quantity::kAngularRate, kDeg / kHour, "rad/s"};
  if (name == "rad/h") return {name, Quantity::kAngularRate, 1.0 / kHour, "rad/s"};
  if (name == "m/s^2" || name == "m/s2") return {name, Quantity::kAcceleration, 1.0, "m/s^2"};
  if (name == "g") return {name, Quantity::kAcceleration, kStandardGravity, "m/s^2"};
  if (name == "mg") return {name, Quantity::kAcceleration, 1e-3 * kStandardGravity, "m/s^2"};
  if (name == "ug") return {name, Quantity::kAcceleration, 1e-6 * kStandardGravity, "m/s^2"};
  if (name == "1" || name == "si" || name == "none") return {name, Quantity::kGeneric, 1.0, "1"};
  throw std::invalid_argument("unknown unit '" + name +
                              "' (expected rad/s, deg/s, deg/h, rad/h, m/s^2, g, mg, ug or 1)");
}

Quantity quantity_of_si_unit(const std::string& si_unit) {
  if (si_unit == "rad/s") return Quantity::kAngularRate;
  if (si_unit == "m/s^2") return Quantity::kAcceleration;
  return Quantity::kGeneric;
}

const char* term_name(Term t) {
  switch (t) {
    case Term::kQ: return "Q";
    case Term::kN: return "N";
    case Term::kB: return "B";
    case Term::kK: return "K";
    case Term::kR: return "R";
  }
  return "?";
}

EngineeringUnit paper_unit(Quantity q, Term t) {
  const double sqrt_h = std::sqrt(kHour);
  if (q == Quantity::kAngularRate) {
    switch (t) {
      case Term::kQ: return {"arcsec", 1.0 / (kDeg / 3600.0)};             // rad -> arcsec
      case Term::kN: return {"deg/sqrt(h)", sqrt_h / kDeg};                // rad/sqrt(s)
      case Term::kB: return {"deg/h", kHour / kDeg};                       // rad/s
      case Term::kK: return {"deg/h/sqrt(h)", kHour * sqrt_h / kDeg};      // rad/s/sqrt(s)
      case Term::kR: return {"deg/h/h", kHour * kHour / kDeg};             // rad/s^2
    }
  }
  if (q == Quantity::kAcceleration) {
    switch (t) {
      case Term::kQ: return {"m/h", kHour};                 // m/s (velocity quantisation)
      case Term::kN: return {"m/s/sqrt(h)", sqrt_h};        // m/s/sqrt(s)
      case Term::kB: return {"m/s/h", kHour};               // m/s^2
      case Term::kK: return {"m/s/h/sqrt(h)", kHour * sqrt_h};
      case Term::kR: return {"m/s/h^2", kHour * kHour};
    }
  }
  switch (t) {  // generic: SI
    case Term::kQ: return {"unit*s", 1.0};
    case Term::kN: return {"unit*sqrt(s)", 1.0};
    case Term::kB: return {"unit", 1.0};
    case Term::kK: return {"unit/sqrt(s)", 1.0};
    case Term::kR: return {"unit/s", 1.0};
  }
  return {"?", 1.0};
}

std::string si_term_unit(const std::string& u, Term t) {
  switch (t) {
    case Term::kQ: return u + "*s";
    case Term::kN: return u + "/sqrt(Hz)";
    case Term::kB: return u;
    case Term::kK: return u + "/sqrt(s)";
    case Term::kR: return u + "/s";
  }
  return u;
}

}  // namespace ldv::allan
