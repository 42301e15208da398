#pragma once
// Alignment settings implied by the filter's stochastic model (used by `ldv nav` and the fusion service).
#include "estimator/ins/alignment.hpp"
#include "estimator/options.hpp"

namespace ldv::est {
AlignmentOptions alignment_options_from(const FilterOptions& fo);
}  // namespace ldv::est
