#!/usr/bin/env bash
# Builds ldvnav with AddressSanitizer + UndefinedBehaviorSanitizer into $2 and runs every unit test and
# the fuzz suites there; any sanitizer report fails the run (halt_on_error, no recovery from UB).
# This build compiles file by file, without precompiled headers: a file that compiles in the default build only
# because a unity batch-mate or the precompiled header included what it uses fails here (cmake/fast_build.cmake).
set -euo pipefail
src="$1" build="$2"
cmake -S "$src" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DLDV_SANITIZE=ON -DLDV_UNITY_BUILD=OFF \
  -DLDV_PRECOMPILE_HEADERS=OFF >/dev/null
cmake --build "$build" -j"$(nproc)"
export ASAN_OPTIONS=halt_on_error=1:detect_leaks=0:abort_on_error=1
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
ctest --test-dir "$build" --output-on-failure -j2 -LE 'montecarlo|integration|sanitize' --timeout 3600
