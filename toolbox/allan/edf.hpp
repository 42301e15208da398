#pragma once
// Equivalent degrees of freedom of the deviation estimates: C. Greenhall and W. Riley,
// "Uncertainty of stability variances based on finite differences" (PTTI 2003), the algorithm
// NIST SP 1065 section 5.3 and Stable32 use for ADEV, OADEV, MDEV, TDEV, HDEV and OHDEV.
#include "toolbox/allan/deviation.hpp"

namespace ldv::allan {

// alpha: power-law exponent of the frequency spectrum S_y(f) ~ f^alpha (+2 white PM ... -4), an
// integer. It is clamped to the range the variance converges for (alpha + 2d > 1: d = 2 for the
// Allan family, 3 for Hadamard). n_phase: number of phase points. Returns 0 when no estimate exists.
double greenhall_edf(Deviation dev, int alpha, long m, long n_phase);

// Lowest alpha the deviation converges for (-2 for Allan/modified Allan, -4 for Hadamard).
int min_convergent_alpha(Deviation dev);

}  // namespace ldv::allan
