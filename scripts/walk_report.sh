#!/usr/bin/env bash
# The real walk (../shared/data/drives/walk_0827): navigation, outage table against the uncut RTK-aided
# solution, diagnosis and an HTML report, from tests/estimator/data/walk_0827_mems.yaml. Needs a build.
#   scripts/walk_report.sh [OUT_DIR]   (default out/walk_0827; open OUT_DIR/report/index.html)
set -euo pipefail
cd "$(dirname "$0")/.."
bin="$PWD/build/bin"
cfg=tests/estimator/data/walk_0827_mems.yaml
out="${1:-$PWD/out/walk_0827}"
rm -rf "$out"; mkdir -p "$out"

echo "== navigation (aligned from the data, RTK positions at 4 Hz)"
"$bin/ldv" nav --kfgins-config "$cfg" --out "$out/walk.nav" --std-rate 10
echo "== outages of 10, 20 and 30 s while walking, against the uncut solution"
"$bin/ldv" outage --kfgins-config "$cfg" --lengths 10,20,30 --converge 20 --recovery 10 --min-speed 0.8 \
  --json "$out/outage.json" --quiet
echo "== diagnosis"
"$bin/ldv" diagnose --kfgins-config "$cfg" --json "$out/diagnosis.json" --quiet
echo "== report"
"$bin/ldv" report --nav "$out/walk.nav" --outage-json "$out/outage.json" --diagnose-json "$out/diagnosis.json" \
  --title "walk_0827: hand-held MEMS IMU + u-blox RTK" --out "$out/report"
echo "== $out/report/index.html"
