#pragma once
// Moved to common/formats/rtklib_solution.hpp; kept only for tests/integration/test_gnss_link.cpp (owned by the
// integration tests): remove once it includes the new path.
#include "common/formats/rtklib_solution.hpp"
