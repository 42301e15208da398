#pragma once
// Moved to common/formats/ubx_framer.hpp; kept only for tests/integration/test_gnss_link.cpp (owned by the
// integration tests): remove once it includes the new path.
#include "common/formats/ubx_framer.hpp"
