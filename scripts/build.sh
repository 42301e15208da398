#!/usr/bin/env bash
# Configures and builds ldvnav into build/ (binaries in build/bin/).
# scripts/build.sh [configure|build]: one phase only (scripts/test.sh times them apart); both by default.
set -euo pipefail
cd "$(dirname "$0")/.."
phase=${1:-all}
if [[ $phase == all || $phase == configure ]]; then
  # Ninja starts a target's compiles before the libraries it links are linked (make waits): a new tree uses it
  # when it is installed; a tree configured before keeps its generator.
  generator=()
  if [[ ! -f build/CMakeCache.txt ]] && command -v ninja >/dev/null; then generator=(-G Ninja); fi
  cmake "${generator[@]}" -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
if [[ $phase == all || $phase == build ]]; then
  cmake --build build -j"$(nproc)"
fi
