#!/usr/bin/env bash
# The paper's Table 12 regenerated (issue 14): GNSS gaps of 1, 2, 5 and 10 min during manoeuvres on the
# simulator's land-vehicle drive, for the paper's three IMUs as its Tables 4-9 identified them (ldv sim's
# *-paper grades), filtered by geoldv51 (the paper's 51 states) with the configuration ldv sim writes for the
# grade; free-inertial in the gaps as the paper's were (ZUPT off), and with ZUPT as a second table. The largest
# |drift| at the end of the gaps of each length (the paper prints single worst cases) beside the paper's numbers,
# read from ../shared/data/paper/geo_ldv_tables.yaml, with the ratio.
#   bench/paper_tables/table12.sh [LDV [OUT_DIR]]      (about 2 min; writes OUT_DIR/table12.md)
# docs/paper_table12.md is its output plus the explanations (bench/paper_tables/table12_notes.md).
set -euo pipefail
cd "$(dirname "$0")/../.."
LDV="${1:-build/bin/ldv}"
OUT="${2:-out/paper_table12}"
PAPER="${LDV_PAPER_TABLES:-../shared/data/paper/geo_ldv_tables.yaml}"
SEED="${LDV_TABLE12_SEED:-11}"
mkdir -p "$OUT"
for grade in hg1700-paper hg1900-paper 3dm-gx2-paper 3dm-gx2-paper-q-arcsec; do
  echo "== $grade: simulating 1 h (seed $SEED)" >&2
  "$LDV" sim --grade "$grade" --seed "$SEED" --duration 3600 --scenario drive --gnss-rate 1 --quiet --out "$OUT/$grade"
  for mode in free zupt; do
    extra=""
    [ "$mode" = free ] && extra="--no-zupt"
    echo "   ldv outage ($mode)" >&2
    "$LDV" outage --kfgins-config "$OUT/$grade/kfgins.yaml" --truth "$OUT/$grade/truth.nav" --model geoldv51 \
      --lengths 60,120,300,600 $extra --json "$OUT/$grade.$mode.json" --quiet > "$OUT/$grade.$mode.txt"
  done
done
python3 bench/paper_tables/table12.py "$OUT" "$PAPER" "$SEED" > "$OUT/table12.md"
cat bench/paper_tables/table12_notes.md >> "$OUT/table12.md"
echo "written $OUT/table12.md" >&2
