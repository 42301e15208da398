#!/usr/bin/env bash
# The test command: install dependencies, build, run the default test suite (everything except the long
# studies: `montecarlo`, the full option fuzz `fuzz`, the ASan+UBSan build `sanitize`; each runs with
# `ctest --test-dir build -L LABEL`). Integration tests run in private network namespaces.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install_deps.sh
scripts/build.sh
ctest --test-dir build --output-on-failure -j2 -LE 'montecarlo|fuzz|sanitize' --timeout 900
