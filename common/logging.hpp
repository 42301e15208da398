#pragma once
// The one logging entry point (spdlog). Tools log to stderr so stdout stays parseable.
#include <spdlog/spdlog.h>

namespace ldv {
void init_logging(bool verbose = false);
}  // namespace ldv
