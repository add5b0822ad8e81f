#!/usr/bin/env bash
# Two builds' cracked step, the issue-43 way: alternating rounds (bench/ab_compare.py) at 1 thread
# on the tension cube from its checkpoint at step 12,000 (300 steps after 20, CUBE_ROUNDS rounds)
# and on the AN4 NL-B beam from its checkpoint at step 112,000 (100 after 50, AN4_ROUNDS rounds),
# and with INTACT_ROUNDS > 0 the intact cube too (1000 after 50).
#
# Usage: bash bench/cracked_ab.sh BIN_A BIN_B CUBE_CHECKPOINT AN4_CHECKPOINT
#   BIN_A, BIN_B: two rcdem_step_bench binaries, each with arguments of its own if quoted as one
#   word (bench/ab_compare.py: "BIN --set solver.KEY=false" BIN times one binary with and without
#   a setting); the checkpoints made by either's step, e.g.
#   rcdem_step_bench examples/uniaxial/tension.toml 1 12000 1 --save-checkpoint DIR
#   rcdem_step_bench examples/three_point_bending/study/AN4_NL-B.toml 1 112000 1 --save-checkpoint DIR
# Environment: CUBE_ROUNDS (8), AN4_ROUNDS (6), INTACT_ROUNDS (0). Prints each comparison's summary
# lines (the medians, the sign test, ab_median_ratio=<B/A>).
set -euo pipefail
cd "$(dirname "$0")/.."
[[ $# -eq 4 ]] || { sed -n '2,15p' "$0" >&2; exit 2; }
A=$1 B=$2 CKC=$3 CKA=$4
CUBE=examples/uniaxial/tension.toml; AN4=examples/three_point_bending/study/AN4_NL-B.toml
export OMP_NUM_THREADS=1
ab() { /usr/bin/python3 bench/ab_compare.py "$@" 2>&1 | grep -v "^round"; }
echo "== cube at step 12,000, 300 steps after 20: A vs B"
ab "${CUBE_ROUNDS:-8}" "$A" "$B" $CUBE 300 20 1 --checkpoint "$CKC"
echo "== AN4 NL-B at step 112,000, 100 steps after 50: A vs B"
ab "${AN4_ROUNDS:-6}" "$A" "$B" $AN4 100 50 1 --checkpoint "$CKA"
if (( ${INTACT_ROUNDS:-0} > 0 )); then
  echo "== intact cube, 1000 steps after 50: A vs B"
  ab "$INTACT_ROUNDS" "$A" "$B" $CUBE 1000 50 1
fi
