#!/usr/bin/env bash
# The paper's Tables 4-9 regenerated (issue 14): the Allan noise terms of its three IMUs, per axis, identified by
# `ldv allan` on simulated static records of the paper's lengths (16 h at 100 Hz for the HG1700 and HG1900, 5 h at
# 20 Hz for the 3DM-GX2, its Section 4.2) made by `ldv sim --scenario static` with the *-paper grades (Tables 4-9 as
# printed; the 3DM-GX2 twice: gyro Q in degrees as printed, and read as arcsec). Each record is analysed twice: as
# `ldv allan` does by default (N, B, K, R by the likelihood of the raw data, the bias model chosen by AIC) and with
# the bias forced to the paper's Gauss-Markov (sigma, T). Every term recovered beside the paper's number, read from
# ../shared/data/paper/geo_ldv_tables.yaml, with the ratio.
#   bench/paper_tables/tables4_9.sh [LDV [OUT_DIR]]      (about 4 min on 2 cores; writes OUT_DIR/tables4_9.md)
# Needs ~2 GB of memory (`ldv sim` of 16 h at 100 Hz holds the run: 1.9 GB) and ~1 GB of disk per Honeywell record
# (only imu.txt and truth_effects.yaml are kept; the truth trajectory and device streams, 1.1 GB more, are deleted).
# docs/paper_tables4_9.md is its output plus the explanations (bench/paper_tables/tables4_9_notes.md).
set -euo pipefail
cd "$(dirname "$0")/../.."
source bench/paper_tables/static_record.sh
LDV="${1:-build/bin/ldv}"
OUT="${2:-out/paper_tables4_9}"
PAPER="${LDV_PAPER_TABLES:-../shared/data/paper/geo_ldv_tables.yaml}"
SEED="${LDV_TABLES4_9_SEED:-11}"
mkdir -p "$OUT"
for spec in hg1700-paper:57600:100 hg1900-paper:57600:100 3dm-gx2-paper:18000:20 3dm-gx2-paper-q-arcsec:18000:20; do
  IFS=: read -r grade duration rate <<< "$spec"
  echo "== $grade: simulating $((duration / 3600)) h static at $rate Hz (seed $SEED)" >&2
  simulate_static_record "$OUT/$grade" "$grade" "$SEED" "$duration" "$rate" "$LDV"
  echo "   ldv allan (bias model by AIC)" >&2
  "$LDV" allan "$OUT/$grade/imu.txt" --json "$OUT/$grade.json" > "$OUT/$grade.txt" 2> "$OUT/$grade.log"
  echo "   ldv allan --gauss-markov" >&2
  "$LDV" allan "$OUT/$grade/imu.txt" --gauss-markov --json "$OUT/$grade.gm.json" \
    > "$OUT/$grade.gm.txt" 2> "$OUT/$grade.gm.log"
done
python3 bench/paper_tables/tables4_9.py "$OUT" "$PAPER" "$SEED" > "$OUT/tables4_9.md"
cat bench/paper_tables/tables4_9_notes.md >> "$OUT/tables4_9.md"
echo "written $OUT/tables4_9.md" >&2
