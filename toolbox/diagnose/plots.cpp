#include "toolbox/diagnose/plots.hpp"

namespace ldv::diag {
int write_plots(const Diagnosis&, const std::string&) { return 0; }
}
