#!/usr/bin/env bash
# The test command: install dependencies, build, run the default test suite (everything except the
# long `montecarlo` studies). Integration tests run in private network namespaces.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install_deps.sh
scripts/build.sh
ctest --test-dir build --output-on-failure -j2 -LE montecarlo --timeout 900
