#!/usr/bin/env bash
# The main job: the whole system on its built-in simulated vehicle, end to end.
#  1. simulate a tactical-grade vehicle whose GNSS antenna sits on a lever arm nobody configured;
#  2. run the vehicle system for real in a private network namespace: the simulated IMU and GNSS
#     receiver on serial ptys in real time, imu_acq, gnss_link, fusion, tspi_pub and lcm-logger;
#     TSPI printed once a second;
#  3. TSPI accuracy against the simulator's truth (the paper's Tables 10-11 layout);
#  4. diagnose the recorded run: the missing effect is named, added, and the error falls.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install_deps.sh
scripts/build.sh
bin="$PWD/build/bin"
out="$PWD/out/main_job"
rm -rf "$out"; mkdir -p "$out"
duration_s="${LDV_MAIN_JOB_DURATION_S:-180}"

echo "== 1. simulated vehicle: hg1700-typical IMU, 5 Hz RTK, hidden GNSS lever arm, ${duration_s} s"
"$bin/ldv" sim --grade hg1700-typical --seed 42 --duration "$duration_s" --scenario scripts/main_job/demo_vehicle.yaml \
  --gnss-rate 5 --effect lever_arm=0.6,-0.4,-1.3 --out "$out/sim" 2>/dev/null

echo "== 2. the vehicle system in real time (private network namespace; TSPI once a second)"
tests/integration/netns_run.sh scripts/main_job/run_vehicle.sh "$out" "$bin"

echo "== 3. recorded run"
"$bin/ldv" export "$out/vehicle.lcmlog" "$out/tspi.lcmlog" --out "$out/recorded"
if "$bin/ldv" compare --help >/dev/null 2>&1; then
  "$bin/ldv" compare "$out/recorded/tspi.nav" "$out/sim/truth.nav" --settle 10
fi

echo "== 4. diagnosis of the recorded run (the configured model does not know the lever arm)"
sed -e "s#^imupath:.*#imupath: $out/recorded/imu.txt#" -e "s#^gnsspath:.*#gnsspath: $out/recorded/gnss.txt#" \
    -e "s#^outputpath:.*#outputpath: $out/recorded#" "$out/sim/kfgins.yaml" > "$out/recorded/kfgins.yaml"
if "$bin/ldv" diagnose --help >/dev/null 2>&1; then
  "$bin/ldv" diagnose --kfgins-config "$out/recorded/kfgins.yaml" --truth "$out/sim/truth.nav" \
    --json "$out/diagnosis.json" --plots "$out/diagnosis"
fi
echo "== results in $out"
