#!/usr/bin/env bash
# The test command: install dependencies, build, run the default test suite (everything except the long
# studies: `montecarlo`, the full option fuzz `fuzz`, the ASan+UBSan build `sanitize`; each runs with
# `ctest --test-dir build -L LABEL`), then every libFuzzer target from the kept corpus with a fixed seed and number
# of inputs, about 15 s each (clang, ASan, UBSan in build-fuzz/; a finding fails the run). Integration tests run in private network namespaces.
# Prints at its end how long each phase took (also when a phase fails).
set -euo pipefail
cd "$(dirname "$0")/.."

phases=()
phase_start=$SECONDS
end_phase() {  # end_phase NAME: record the phase that just ended
  phases+=("$(printf '%-10s %4d s' "$1" $((SECONDS - phase_start)))")
  phase_start=$SECONDS
}
current=install
print_phases() {
  local rc=$?
  ((rc == 0)) || end_phase "$current (failed, exit $rc)"
  echo "== scripts/test.sh phases (wall clock):"
  printf '   %s\n' "${phases[@]}"
  printf '   %-10s %4d s\n' total "$SECONDS"
}
trap print_phases EXIT

scripts/install_deps.sh
end_phase install
current=configure
scripts/build.sh configure
end_phase configure
current=build
scripts/build.sh build
end_phase build
current=test
ctest --test-dir build --output-on-failure -j2 -LE 'montecarlo|fuzz|sanitize' --timeout 900
end_phase test
current=fuzz
tests/fuzz/run_libfuzzer.sh "$PWD" "$PWD/build-fuzz" "${LDV_CI_FUZZ_SECONDS:-15}" --ci
end_phase fuzz
