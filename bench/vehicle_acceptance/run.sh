#!/bin/bash
# The real-vehicle acceptance matrix (issue 12): `ldv sim --realism vehicle` drives (MEMS 3dm-gx2-typical and
# tactical hg1700-typical, 1 and 4 Hz RTK, seeds 1-4, 400 s) and four single-effect drives, each run from the
# datasheet config a new user writes (no initial state, lever arm or latency) through `ldv nav`, `ldv compare`
# against the truth and, for MEMS at 1 and 4 Hz, `ldv diagnose --iterate`. One ldv process at a time (nice 10),
# ~3 min.
# Usage: bench/vehicle_acceptance/run.sh [LDV [OUT_DIR]]  (defaults build/bin/ldv, out/vehicle_acceptance)
#   -> OUT_DIR/runs/<name>/..., OUT_DIR/results.jsonl, OUT_DIR/results_table.md (the criteria at its end)
set -u
HERE=$(cd "$(dirname "$0")" && pwd)
LDV=$(realpath "${1:-$HERE/../../build/bin/ldv}")
A=$(realpath -m "${2:-$HERE/../../out/vehicle_acceptance}")
mkdir -p "$A"
cd $A
mkdir -p runs
: > results.jsonl
make_datasheet() {  # single-effect runs write no datasheet.yaml: kfgins.yaml minus the initial state, datasheet init stds
  local d=$1
  grep -v -E '^(initpos|initvel|initatt):' $d/kfgins.yaml \
  | sed -E 's/^initposstd:.*/initposstd: [1, 1, 1]  # N E D [m]/; s/^initvelstd:.*/initvelstd: [0.1, 0.1, 0.1]  # N E D [m\/s]/; s/^initattstd:.*/initattstd: [1, 1, 1]  # roll pitch yaw [deg]/' \
  | grep -v -E '^  (simulator:|grade:|seed:|scenario:|  grade:|  seed:|  scenario:)|gnss_latency_s' > $d/datasheet.yaml
}
one() {  # name grade seed rate diag(0/1) extra-sim-args...
  local name=$1 grade=$2 seed=$3 rate=$4 diag=$5; shift 5
  local d=$A/runs/$name
  rm -rf $d
  nice -n 10 $LDV sim --grade $grade --seed $seed --duration 400 --gnss-rate $rate "$@" --out $d --quiet 2> $A/runs/$name.sim.stderr
  echo $? > $A/runs/$name.sim.rc
  [ -f $d/datasheet.yaml ] || make_datasheet $d
  local t0=$(date +%s.%N)
  nice -n 10 $LDV nav --kfgins-config $d/datasheet.yaml --out $d/out.nav 2> $d/nav.stderr
  echo $? > $d/nav.rc
  echo "$(date +%s.%N) - $t0" | bc > $d/nav.wall
  nice -n 10 $LDV compare --json $d/out.nav $d/truth.nav > $d/compare.json 2> $d/compare.stderr
  # The oracle: the same config with the IMU's white noise as installed (the simulator's vibration factor).
  local vib=$(grep -A1 '^  vibration_white_factor:' $d/truth_effects.yaml | sed -n 's/.*si: \[\([0-9.e+-]*\)\].*/\1/p')
  if [ -n "$vib" ]; then
    python3 - "$d/datasheet.yaml" "$vib" > $d/oracle.yaml <<'PY'
import re, sys
text, f = open(sys.argv[1]).read(), float(sys.argv[2])
scale = lambda m: m.group(1) + "[" + ", ".join("%g" % (float(x) * f) for x in m.group(2).split(",")) + "]"
print(re.sub(r"(\n  (?:arw|vrw): )\[([^\]]*)\]", scale, text), end="")
PY
    nice -n 10 $LDV nav --kfgins-config $d/oracle.yaml --out $d/oracle.nav 2> $d/oracle.stderr
  fi
  if [ $diag = 1 ]; then
    local t1=$(date +%s.%N)
    nice -n 10 $LDV diagnose --kfgins-config $d/datasheet.yaml --iterate --truth $d/truth.nav --json $d/diag.json > $d/diag.stdout 2> $d/diag.stderr
    echo $? > $d/diag.rc
    echo "$(date +%s.%N) - $t1" | bc > $d/diag.wall
  fi
  nice -n 10 python3 $HERE/analyze.py $d $name >> results.jsonl
  echo "done $name"
}
for grade in 3dm-gx2-typical hg1700-typical; do
  g=$([ $grade = 3dm-gx2-typical ] && echo mems || echo tact)
  for rate in 1 4; do
    for seed in 1 2 3 4; do
      one ${g}_${rate}hz_s$seed $grade $seed $rate $([ $g = mems ] && echo 1 || echo 0) --realism vehicle
    done
  done
done
one single_vibration 3dm-gx2-typical 1 4 0 --vibration 10
one single_latency   3dm-gx2-typical 1 4 0 --imu-latency 0.25
one single_mounting  3dm-gx2-typical 1 4 0 --mounting 0,0,180
one single_outliers  3dm-gx2-typical 1 4 0 --gnss-outliers 0.01
python3 "$HERE/report.py" "$A" > /dev/null
echo "$A/results_table.md"
