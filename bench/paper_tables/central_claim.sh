#!/usr/bin/env bash
# The paper's central claim, measured (issue 14): an IMU error model identified by Allan analysis gives a better
# navigation solution in GNSS outages than the datasheet model. For each of the paper's three IMUs (ldv sim's
# *-paper grades) ONE 1 h drive (seed SEED, the `drive` scenario, 1 Hz RTK: as table12.sh) is filtered by
# `ldv outage` (geoldv51, gaps of 60/120/300 s during manoeuvres, free-inertial --no-zupt, against the truth)
# with three configurations that differ only in the IMU noise model:
#   datasheet  written from the paper's Table 3 as a new user would (central_claim.py, `configs`; every value
#              and its source in the report, the choices and unit conversions in central_claim_notes.md)
#   allan      `ldv allan --noise-config` on a simulated static record of the same sensor (the paper's lengths:
#              16 h at 100 Hz for the Honeywells, 5 h at 20 Hz for the 3DM-GX2), merged into the drive's config
#              (imunoise's arw/vrw/gbstd/abstd/corrtime and the ldv: moving_bias_* keys replaced, nothing else)
#   true       the kfgins.yaml `ldv sim` writes for the grade
# and, to show where the differences come from, three variants (noise model as configured only): the datasheet
# model with the true white noise, the datasheet model with the true moving-bias terms, the true model with its
# scale-factor states held nearly constant (corrtime 100 h: KF-GINS's corrtime also sets the scale states' GM).
# Each configuration runs twice: with the noise model exactly as configured (ldv.adapt_imu_noise: false) and with
# ldv's defaults (the filter raises its white noise to what a standstill in the data shows, then adapts it to the
# GNSS NIS). Drift (mean and max horizontal at the gap ends) and consistency (share of the end position components
# inside the filter's 3 sigma, mean NEES of the end position errors) side by side, ratios to the true model, the
# paper's Table 12 beside (read from ../shared/data/paper/geo_ldv_tables.yaml).
#   bench/paper_tables/central_claim.sh [LDV [OUT_DIR]]      (writes OUT_DIR/central_claim.md)
# About 4 min on 2 shared cores with tables4_9.sh's static records, 5.5 min when it simulates them.
# Static records: reused from LDV_CENTRAL_CLAIM_STATIC (default out/paper_tables4_9, written by tables4_9.sh) when
# they are the same grade, seed, length and rate; otherwise simulated into OUT_DIR/static (~2 GB of memory and
# ~1 GB of disk per Honeywell record; only imu.txt and truth_effects.yaml are kept).
# docs/paper_central_claim.md is its output plus the explanations (bench/paper_tables/central_claim_notes.md).
set -euo pipefail
cd "$(dirname "$0")/../.."
source bench/paper_tables/static_record.sh
LDV="${1:-build/bin/ldv}"
OUT="${2:-out/paper_central_claim}"
PAPER="${LDV_PAPER_TABLES:-../shared/data/paper/geo_ldv_tables.yaml}"
SEED="${LDV_CENTRAL_CLAIM_SEED:-11}"
STATIC_SEED="${LDV_CENTRAL_CLAIM_STATIC_SEED:-11}"   # tables4_9.sh's default: its records can be reused
STATIC="${LDV_CENTRAL_CLAIM_STATIC:-out/paper_tables4_9}"
PY=bench/paper_tables/central_claim.py
RUN=(nice -n 10 "$LDV")   # a shared machine
SECONDS=0
mkdir -p "$OUT"

for spec in hg1700-paper:57600:100 hg1900-paper:57600:100 3dm-gx2-paper:18000:20; do
  IFS=: read -r grade duration rate <<< "$spec"
  dir="$OUT/$grade"
  rm -rf "$dir"
  mkdir -p "$dir"

  # 1. The static record for the Allan analysis: reuse tables4_9.sh's when it is the same record.
  record="$STATIC/$grade"
  if python3 "$PY" check-static "$record" "$grade" "$STATIC_SEED" "$duration" "$rate"; then
    echo "== $grade: reusing the static record $record/imu.txt" >&2
  else
    record="$OUT/static/$grade"
    echo "== $grade: simulating $((duration / 3600)) h static at $rate Hz (seed $STATIC_SEED)" >&2
    simulate_static_record "$record" "$grade" "$STATIC_SEED" "$duration" "$rate" "${RUN[@]}"
  fi
  echo "   ldv allan --noise-config" >&2
  "${RUN[@]}" allan "$record/imu.txt" --noise-config "$dir/allan_noise.yaml" --json "$dir/allan.json" \
    > "$dir/allan.txt" 2> "$dir/allan.log"
  echo "$record" > "$dir/static_record.txt"

  # 2. The drive, as table12.sh simulates it (device byte streams dropped: no step here reads them).
  echo "   simulating the 1 h drive (seed $SEED)" >&2
  "${RUN[@]}" sim --grade "$grade" --seed "$SEED" --duration 3600 --scenario drive --gnss-rate 1 --quiet --out "$dir/drive"
  rm -f "$dir/drive/imu_device.bin" "$dir/drive/device_schedule.txt" "$dir/drive/gnss.nmea"

  # 3. The three configurations, each with the noise model as configured and with ldv's adaptive default.
  python3 "$PY" configs "$PAPER" "$grade" "$dir/drive/kfgins.yaml" "$dir/allan_noise.yaml" "$dir"
  for model in datasheet allan true; do
    for mode in configured adaptive; do
      echo "   ldv outage: $model model, $mode" >&2
      "${RUN[@]}" outage --kfgins-config "$dir/$model.$mode.yaml" --truth "$dir/drive/truth.nav" --model geoldv51 \
        --lengths 60,120,300 --no-zupt --json "$dir/$model.$mode.json" --quiet > "$dir/$model.$mode.txt"
    done
    # What the adaptive default does to the configured white noise: ldv nav's summary lines (the floor a
    # standstill in the drive shows, times the NIS adaptation; a density configured as 0 and what it took).
    "${RUN[@]}" nav --kfgins-config "$dir/$model.adaptive.yaml" --model geoldv51 --out "$dir/nav_tmp.nav" 2>&1 >/dev/null |
      tr '\r' '\n' | grep -E 'IMU noise as installed|was 0 on' > "$dir/$model.adaptive.noise.txt" || true
    rm -f "$dir/nav_tmp.nav" "$dir/nav_tmp_std.txt" "$dir/nav_tmp_innovations.txt"
  done
  # 4. Where the differences come from: the datasheet model with one group of the true terms swapped in, and the
  # true model with its scale-factor states held (nearly) constant, as the simulated scale is (configured only).
  for variant in datasheet_true_white datasheet_true_bias true_constant_scale; do
    echo "   ldv outage: $variant, configured" >&2
    "${RUN[@]}" outage --kfgins-config "$dir/$variant.configured.yaml" --truth "$dir/drive/truth.nav" --model geoldv51 \
      --lengths 60,120,300 --no-zupt --json "$dir/$variant.configured.json" --quiet > "$dir/$variant.configured.txt"
  done
done
echo "== tables (${SECONDS} s so far)" >&2
python3 "$PY" table "$OUT" "$PAPER" "$SEED" "$STATIC_SEED" "$SECONDS" > "$OUT/central_claim.md"
cat bench/paper_tables/central_claim_notes.md >> "$OUT/central_claim.md"
echo "written $OUT/central_claim.md (${SECONDS} s)" >&2
