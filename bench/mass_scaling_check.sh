#!/usr/bin/env bash
# What selective mass scaling (solver.added_mass_limit, docs/model.md 6) does to the study's quick
# beams: each case x packing seed x added-mass budget is run from the study's quick scenario with
# only the seed and the budget changed, and the peaks are printed beside the unscaled run's.
# A peak that moved by more than the rate criterion of SPEC 6 (2%) would argue against the budget.
#
# Usage: bash bench/mass_scaling_check.sh [CASES="AN0 AN4_NL-B"] [SEEDS="1 2 3 4"] [LIMITS="0.005 0.03"]
#   (environment: BUILD_DIR=build, OUT=a fresh temporary folder, OMP_NUM_THREADS as given)
# Prints one line per run, then `max_abs_peak_change_percent=<x>` over every scaled run.
set -euo pipefail
cd "$(dirname "$0")/.."
CASES=${1:-"AN0 AN4_NL-B"}
SEEDS=${2:-"1 2 3 4"}
LIMITS=${3:-"0.005 0.03"}
BUILD_DIR=${BUILD_DIR:-build}
OUT=${OUT:-$(mktemp -d /tmp/rcdem_mass_scaling.XXXXXX)}
RCDEM=$BUILD_DIR/rcdem
[ -x "$RCDEM" ] || { echo "mass_scaling_check: $RCDEM not built (bash scripts/setup.sh)" >&2; exit 1; }
QUICK=examples/three_point_bending/study/quick
contact=$(realpath examples/calibrated_contact.toml)
mkdir -p "$OUT"
echo "# case seed added_mass_limit peak_N deflection_at_peak_mm steps time_step_s change_percent (runs in $OUT)"
worst=0
for case in $CASES; do
  [ -f "$QUICK/$case.toml" ] || { echo "mass_scaling_check: no scenario $QUICK/$case.toml" >&2; exit 1; }
  for seed in $SEEDS; do
    base=""
    for limit in 0 $LIMITS; do
      name=${case}_seed${seed}_m${limit}
      # The quick scenario with its include made absolute, the seed and the budget set.
      sed -e "s#^include = .*#include = [\"$contact\"]#" -e "s/^seed = .*/seed = $seed/" \
        -e "s/^\[solver\]/[solver]\nadded_mass_limit = $limit/" -e "s/^snapshots = .*/snapshots = 0/" \
        "$QUICK/$case.toml" >"$OUT/$name.toml"
      "$RCDEM" -q run "$OUT/$name.toml" -o "$OUT/$name" --force
      line=$(/usr/bin/python3 - "$OUT/$name/summary.json" <<'EOF'
import json, sys
j = json.load(open(sys.argv[1]))
print(f"{j['peak_load_N']:.1f} {abs(j['displacement_at_peak_m']) * 1e3:.3f} {j['steps']} {j['time_step_s']:.4g}")
EOF
)
      peak=${line%% *}
      [ -z "$base" ] && base=$peak
      change=$(/usr/bin/python3 -c "print(f'{100 * ($peak / $base - 1):+.2f}')")
      echo "$case $seed $limit $line $change"
      worst=$(/usr/bin/python3 -c "print(max($worst, abs($change)))")
    done
  done
done
echo "max_abs_peak_change_percent=$worst"
