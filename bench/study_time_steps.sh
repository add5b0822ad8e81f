#!/usr/bin/env bash
# Issue 26: each full-size study case's time step, per-body (the old set-up: 0.5 x the estimate)
# and assembled (the new one: 0.8 x 2 / omega_max), from one step of each scenario.
#   bash bench/study_time_steps.sh [RCDEM=build/rcdem]  -> results/study_time_steps/table.txt
set -euo pipefail
cd "$(dirname "$0")/.."
RCDEM=${1:-build/rcdem}
OUT=results/study_time_steps
mkdir -p "$OUT"
for f in examples/three_point_bending/study/*.toml; do
  c=$(basename "$f" .toml)
  [ -f "$OUT/$c.log" ] && grep -q "^time step" "$OUT/$c.log" && continue
  # The scenario with its include made absolute and its stop rules replaced by one step.
  sed -e "s|include = \[\"../../calibrated_contact.toml\"\]|include = [\"$PWD/examples/calibrated_contact.toml\"]|" \
      -e 's|^displacement = .*|steps = 1|' -e '/^load_drop = /d' -e '/^post_peak_displacement = /d' \
      -e 's|^snapshots = .*|snapshots = 0|' "$f" >"$OUT/$c.toml"
  OMP_NUM_THREADS=1 "$RCDEM" run "$OUT/$c.toml" -o "$OUT/$c" --force 2>&1 | grep "^time step" >"$OUT/$c.log"
done
for f in "$OUT"/*.log; do
  c=$(basename "$f" .log)
  sed -E "s|^time step ([0-9.e+-]+) s .*omega_max ([0-9.e+-]+) rad/s.*per-body estimate ([0-9.e+-]+) s.*|$c \1 \3|" "$f"
done | awk '{printf "%-10s new %.4g s  old %.4g s  ratio %.3f\n", $1, $2, 0.5 * $3, $2 / (0.5 * $3)}' | tee "$OUT/table.txt"
