#!/usr/bin/env bash
# The vehicle bus benchmark (issue 4, issue 13): IMU-in -> NAV/TSPI-out latency (p50 ... p99.9, max),
# loss, and CPU of each service at a 600 Hz IMU and 20 Hz GNSS, with the real services, inside a
# private network namespace (loopback multicast only), run with the scheduling the units ship
# (deploy/systemd: real-time FIFO for imu_acq, fusion, tspi_pub, pinned to core 0; needs root for that).
# usage: scripts/bench_bus.sh [BUILD_DIR] [--hog | --hog-all] [--no-sched] [ldv_bus_bench options]
#   --hog       a CPU hog (a busy loop) pinned to every core but core 0: "the other core" on a 2-core box
#   --hog-all   a busy loop on every core (nothing left idle)
#   --no-sched  the services at the default scheduling (SCHED_OTHER, nice 0), to compare
#   scripts/bench_bus.sh build --hog --duration 120   # the latency-under-load figure of deploy/README.md
#   scripts/bench_bus.sh build --duration 600         # the 10-minute loss run
set -euo pipefail
cd "$(dirname "$0")/.."
build=build
if [[ $# -gt 0 && $1 != -* ]]; then build="$1"; shift; fi
bin="$PWD/$build/bin"
[[ -x "$bin/ldv_bus_bench" ]] || { echo "build first: cmake --build $build --target ldv_bus_bench fusion tspi_pub imu_acq gnss_link ldv ldv_logger"; exit 1; }
hog_cpus=(); sched=(--units "$PWD/deploy/systemd"); args=()
ncpu="$(nproc)"
for a in "$@"; do
  case "$a" in
    --hog) for ((c = 1; c < ncpu; ++c)); do hog_cpus+=("$c"); done ;;
    --hog-all) for ((c = 0; c < ncpu; ++c)); do hog_cpus+=("$c"); done ;;
    --no-sched) sched=() ;;
    *) args+=("$a") ;;
  esac
done
if [[ ${#sched[@]} -gt 0 && $(id -u) != 0 ]]; then
  echo "real-time scheduling as the units ship it needs root; running with --no-sched" >&2; sched=()
fi
# CPUAffinity= of the latency path's units: the bench (publisher standing in for imu_acq, receiver) and
# every service it starts run there; stricter than the units, where gnss_link and the logger float.
pin=()
if [[ ${#sched[@]} -gt 0 ]]; then
  affinity="$(sed -n 's/^CPUAffinity=//p' deploy/systemd/ldvnav-fusion.service)"
  [[ -z "$affinity" ]] || { pin=(taskset -c "${affinity// /,}"); echo "latency path on core(s) $affinity (CPUAffinity= of the units)" >&2; }
fi
hogs=()
cleanup() { for p in "${hogs[@]}"; do kill "$p" 2>/dev/null || true; done; }
trap cleanup EXIT
for c in "${hog_cpus[@]}"; do
  taskset -c "$c" bash -c 'while :; do :; done' & hogs+=($!)
done
[[ ${#hogs[@]} -eq 0 ]] || echo "CPU hog: a busy loop on core(s) ${hog_cpus[*]} (pids ${hogs[*]})" >&2
${pin[@]+"${pin[@]}"} tests/integration/netns_run.sh "$bin/ldv_bus_bench" --bin "$bin" "${sched[@]}" "${args[@]}"
