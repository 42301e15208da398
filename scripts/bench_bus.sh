#!/usr/bin/env bash
# The vehicle bus benchmark (issue 4): IMU-in -> NAV/TSPI-out latency (p50/p99), loss, and CPU of each
# service at a 600 Hz IMU and 20 Hz GNSS, with the real services, inside a private network namespace
# (loopback multicast only). usage: scripts/bench_bus.sh [BUILD_DIR] [ldv_bus_bench options]
#   scripts/bench_bus.sh build --duration 600      # the 10-minute loss run
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"; shift || true
bin="$PWD/$build/bin"
[[ -x "$bin/ldv_bus_bench" ]] || { echo "build first: cmake --build $build --target ldv_bus_bench fusion tspi_pub imu_acq gnss_link ldv"; exit 1; }
exec tests/integration/netns_run.sh "$bin/ldv_bus_bench" --bin "$bin" "$@"
