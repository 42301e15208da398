#!/usr/bin/env bash
# The paper's Tables 10-11 regenerated (issue 14): two IMUs on one simulated vehicle, each through its own
# filter, their solutions differenced after the paper's 300 s tuning period. Table 10: HG1700 and 3DM-GX2 on a
# 12.5 km drive, Table 11: HG1900 and 3DM-GX2 on 10.5 km (lengths and tuning period read from the paper's YAML).
# One vehicle = one trajectory (ldv sim's trajectory is the scenario's, whatever the seed) and one GNSS
# receiver. ldv sim draws every error from the seed by source name ("turn_on", "gyro_white", "gnss_white", ...),
# so two grades simulated with the same seed get the same normal draws scaled by their sigmas: perfectly
# correlated sensor errors. The second IMU is therefore simulated with its own seed (SEED + 1000) and run on
# the first IMU's gnss.txt (RTK-fixed, the paper's dual-frequency receiver). The paper ran the 3DM-GX2 of Table
# 10 on L1-only GNSS; ldv sim has no L1 grade, so two stand-ins bracket it: float RTK and single point, each a
# receiver of its own (GNSS-only simulations, seed SEED + 1000). Every 3DM-GX2 solution is made in both readings
# of the paper's gyro Q (3dm-gx2-paper: degrees as printed; 3dm-gx2-paper-q-arcsec), with the same sensor draws.
# Filter: geoldv51 with the configuration ldv sim writes for each grade. ldv compare: tactical minus 3DM-GX2.
#   bench/paper_tables/tables10_11.sh [LDV [OUT_DIR]]      (about 2 min; writes OUT_DIR/tables10_11.md)
# docs/paper_tables10_11.md is its output plus the explanations (bench/paper_tables/tables10_11_notes.md).
set -euo pipefail
cd "$(dirname "$0")/../.."
LDV="${1:-build/bin/ldv}"
OUT="${2:-out/paper_tables10_11}"
PAPER="${LDV_PAPER_TABLES:-../shared/data/paper/geo_ldv_tables.yaml}"
SEED="${LDV_TABLES10_11_SEED:-11}"
SEED2=$((SEED + 1000))
PY=bench/paper_tables/tables10_11.py
mkdir -p "$OUT"

# Drop what no step here reads (device byte streams; for GNSS-only runs also the IMU and the truth).
slim() { rm -f "$1/imu_device.bin" "$1/device_schedule.txt" "$1/gnss.nmea"; }

# How long the built-in drive takes to cover the paper's drive lengths: a noiseless 20 Hz truth.
echo "== planning: the drive's length against time" >&2
"$LDV" sim --grade perfect --no-noise --seed "$SEED" --duration 1800 --imu-rate 20 --scenario drive --quiet --out "$OUT/route"
slim "$OUT/route"
read -r DUR10 DUR11 SETTLE < <(python3 "$PY" --plan "$PAPER" "$OUT/route/truth.nav")
echo "   Table 10: ${DUR10} s, Table 11: ${DUR11} s, differences after ${SETTLE} s" >&2

nav() {  # nav KFGINS_DIR GNSS_TXT OUT_NAV: geoldv51, the summary kept in OUT_NAV.log
  "$LDV" nav --kfgins-config "$1/kfgins.yaml" --gnss "$2" --model geoldv51 --out "$3" 2>&1 >/dev/null |
    tr '\r' '\n' | grep -v ' %$' > "${3%.nav}.log"
}

for spec in "10 hg1700-paper $DUR10" "11 hg1900-paper $DUR11"; do
  read -r table tactical dur <<< "$spec"
  dir="$OUT/table$table"
  mkdir -p "$dir/nav" "$dir/compare"
  echo "== Table $table: $tactical (seed $SEED) and 3DM-GX2 (seed $SEED2), ${dur} s" >&2
  "$LDV" sim --grade "$tactical" --seed "$SEED" --duration "$dur" --scenario drive --gnss-rate 1 --quiet --out "$dir/$tactical"
  slim "$dir/$tactical"
  for grade in 3dm-gx2-paper 3dm-gx2-paper-q-arcsec; do
    "$LDV" sim --grade "$grade" --seed "$SEED2" --duration "$dur" --scenario drive --gnss-rate 1 --quiet --out "$dir/$grade"
    slim "$dir/$grade"
    cmp -s "$dir/$tactical/truth.nav" "$dir/$grade/truth.nav" ||
      { echo "tables10_11.sh: $grade's truth differs from $tactical's: not one vehicle" >&2; exit 1; }
    rm -f "$dir/$grade/truth.nav"  # the same bytes as the tactical IMU's
  done
  for mode in float single; do
    "$LDV" sim --grade perfect --seed "$SEED2" --duration "$dur" --scenario drive --gnss-rate 1 --gnss-mode "$mode" \
      --quiet --out "$dir/l1-$mode"
    slim "$dir/l1-$mode"
    rm -f "$dir/l1-$mode/imu.txt" "$dir/l1-$mode/truth.nav"
  done
  echo "   ldv nav (geoldv51) and ldv compare" >&2
  nav "$dir/$tactical" "$dir/$tactical/gnss.txt" "$dir/nav/$tactical.nav"
  "$LDV" compare "$dir/nav/$tactical.nav" "$dir/$tactical/truth.nav" --settle "$SETTLE" --json \
    > "$dir/compare/$tactical.truth.json"
  for grade in 3dm-gx2-paper 3dm-gx2-paper-q-arcsec; do
    for gnss in rtk l1-float l1-single; do
      gnss_txt="$dir/$gnss/gnss.txt"
      [ "$gnss" = rtk ] && gnss_txt="$dir/$tactical/gnss.txt"
      nav "$dir/$grade" "$gnss_txt" "$dir/nav/$grade.$gnss.nav"
      "$LDV" compare "$dir/nav/$tactical.nav" "$dir/nav/$grade.$gnss.nav" --settle "$SETTLE" --json \
        > "$dir/compare/$grade.$gnss.json"
      "$LDV" compare "$dir/nav/$grade.$gnss.nav" "$dir/$tactical/truth.nav" --settle "$SETTLE" --json \
        > "$dir/compare/$grade.$gnss.truth.json"
    done
  done
done
python3 "$PY" "$OUT" "$PAPER" "$SEED" > "$OUT/tables10_11.md"
cat bench/paper_tables/tables10_11_notes.md >> "$OUT/tables10_11.md"
echo "written $OUT/tables10_11.md" >&2
