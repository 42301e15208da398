#!/usr/bin/env bash
# The coverage-guided fuzz run (label `fuzz`): builds the fuzz targets with clang, libFuzzer, ASan and UBSan into
# $2 (installs clang and its runtime from Debian when missing) and runs each for $3 seconds from the kept corpus
# (tests/fuzz/corpus/<target>, read only: new inputs go to $2/corpus-new/<target>). A crash, a sanitizer report or
# a broken property (tests/fuzz/fuzz_support.hpp) fails the run; the input is left in $2/findings/.
# Add an input that found something to the kept corpus once it is fixed: the default suite replays it.
# With a 4th argument `--merge`, the inputs of this run that reach code the kept corpus does not are merged into
# it (libFuzzer -merge=1: the grown corpus minimised), to be committed.
# scripts/test.sh (and so CI) runs it on every submission as `--ci`: each target from the kept corpus with a fixed
# seed for a fixed number of inputs (about 15 s each on 2 cores; SECONDS then only caps a slow machine), so a
# submission's run is the one its author ran: a finding is the code's, not the luck of the draw.
set -euo pipefail
src="$1" build="$2" seconds="${3:-30}" merge="${4:-}"
declare -A ci_runs=([fuzz_kfgins_text]=30000 [fuzz_rtklib_files]=17000 [fuzz_user_tables]=15000 [fuzz_gnss_stream]=80000
  [fuzz_imu_device]=150000 [fuzz_lcm_log]=60000 [fuzz_yaml_configs]=25000 [fuzz_bus_gate]=120)
if ! command -v clang++ >/dev/null || ! ls /usr/lib/llvm-*/lib/clang/*/lib/linux/libclang_rt.fuzzer-x86_64.a >/dev/null 2>&1; then
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq && apt-get install -y -qq --no-install-recommends clang libclang-rt-14-dev
fi
targets=(fuzz_kfgins_text fuzz_rtklib_files fuzz_user_tables fuzz_gnss_stream fuzz_imu_device fuzz_lcm_log fuzz_yaml_configs fuzz_bus_gate)
# -fsanitize=fuzzer-no-link: every library carries libFuzzer's coverage counters; vptr off as in LDV_SANITIZE.
flags="-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize=vptr -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
cmake -S "$src" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ -DLDV_LIBFUZZER=ON \
  -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" >/dev/null
cmake --build "$build" -j"$(nproc)" --target "${targets[@]}"
export ASAN_OPTIONS=halt_on_error=1:detect_leaks=0:abort_on_error=1
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
mkdir -p "$build/findings"
status=0
for t in "${targets[@]}"; do
  mkdir -p "$build/corpus-new/$t"
  bound=(-max_total_time="$seconds")
  if [[ "$merge" == --ci ]]; then
    bound=(-seed=1 -runs="${ci_runs[$t]}" -max_total_time="$((4 * seconds))")
    rm -rf "$build/corpus-new/$t" && mkdir -p "$build/corpus-new/$t"  # the kept corpus alone: the same run each time
  fi
  echo "== $t: ${bound[*]} from $(ls "$src/tests/fuzz/corpus/$t" | wc -l) kept inputs"
  if ! "$build/bin/$t" "${bound[@]}" -timeout=10 -rss_limit_mb=2048 -max_len=65536 \
      -artifact_prefix="$build/findings/$t-" -print_final_stats=1 \
      "$build/corpus-new/$t" "$src/tests/fuzz/corpus/$t" 2>"$build/$t.log"; then
    echo "FINDING in $t (see $build/$t.log and $build/findings/)"
    tail -40 "$build/$t.log"
    status=1
  else
    grep -E "stat::number_of_executed_units|cov:" "$build/$t.log" | tail -2
    if [[ "$merge" == --merge ]]; then
      before=$(ls "$src/tests/fuzz/corpus/$t" | wc -l)
      "$build/bin/$t" -merge=1 -timeout=10 -rss_limit_mb=2048 -max_len=65536 "$src/tests/fuzz/corpus/$t" \
        "$build/corpus-new/$t" 2>"$build/$t.merge.log"
      echo "   merged: $before -> $(ls "$src/tests/fuzz/corpus/$t" | wc -l) kept inputs"
    fi
  fi
done
exit $status
