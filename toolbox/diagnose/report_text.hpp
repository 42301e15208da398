#pragma once
// The terminal report of a diagnosis: model check, screening table, confirmations, verdict, before/after.
#include <iosfwd>

#include "toolbox/diagnose/diagnosis.hpp"

namespace ldv::diag {
void print_report(std::ostream& out, const Diagnosis& d);
}
