#!/usr/bin/env bash
# Builds ldvnav with AddressSanitizer + UndefinedBehaviorSanitizer into $2 and runs every unit test and
# the fuzz suites there; any sanitizer report fails the run (halt_on_error, no recovery from UB).
set -euo pipefail
src="$1" build="$2"
cmake -S "$src" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DLDV_SANITIZE=ON >/dev/null
cmake --build "$build" -j"$(nproc)"
export ASAN_OPTIONS=halt_on_error=1:detect_leaks=0:abort_on_error=1
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
ctest --test-dir "$build" --output-on-failure -j2 -LE 'montecarlo|integration|sanitize' --timeout 3600
