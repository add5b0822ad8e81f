#!/usr/bin/env bash
# The step with and without damaged contacts held to their sums (solver.hold_unloading_contacts,
# contact/held_contacts.hpp), one binary, alternating rounds (bench/ab_compare.py): A holds none,
# B holds them. From a checkpoint past the peak, where most damaged contacts unload.
#
# Usage: bash bench/hold_ab.sh SCENARIO CHECKPOINT [ROUNDS=8] [STEPS=300] [BUILD=build]
#   e.g. (the cracked cube: its checkpoint from
#   `build/bench/rcdem_step_bench examples/uniaxial/tension.toml 1 12000 1 --save-checkpoint DIR`)
#   OMP_NUM_THREADS=1 bash bench/hold_ab.sh examples/uniaxial/tension.toml \
#     DIR/checkpoint_000000012000.h5 10
# Writes the two copies of SCENARIO next to it (its includes are relative), as
# .hold_ab_<name>_{false,true}.toml, and removes them when it ends. Prints ab_compare.py's lines;
# the last is ab_median_ratio=<B/A>.
set -euo pipefail
cd "$(dirname "$0")/.."
[[ $# -ge 2 ]] || { sed -n '2,13p' "$0" >&2; exit 2; }
scenario=$1
checkpoint=$2
rounds=${3:-8}
steps=${4:-300}
build=${5:-build}
bench="$PWD/$build/bench/rcdem_step_bench"
[[ -x "$bench" ]] || { echo "missing $bench: ninja -C $build rcdem_step_bench" >&2; exit 1; }
[[ -f "$scenario" && -f "$checkpoint" ]] || { echo "no such scenario or checkpoint" >&2; exit 1; }
if grep -q '^hold_unloading_contacts' "$scenario"; then
  echo "$scenario sets hold_unloading_contacts itself" >&2
  exit 1
fi
dir=$(cd "$(dirname "$scenario")" && pwd)
name=$(basename "$scenario" .toml)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp" "$dir/.hold_ab_${name}_false.toml" "$dir/.hold_ab_${name}_true.toml"' EXIT
for v in false true; do
  copy="$dir/.hold_ab_${name}_$v.toml"
  awk -v v="$v" '{ print } /^\[solver\]/ { print "hold_unloading_contacts = " v; done = 1 }
      END { if (!done) { print "[solver]"; print "hold_unloading_contacts = " v } }' \
      "$scenario" > "$copy"
  printf '#!/bin/sh\nexec "%s" "%s" "$@"\n' "$bench" "$copy" > "$tmp/$v.sh"
  chmod +x "$tmp/$v.sh"
done
echo "date: $(date -u '+%F %H:%M') UTC  nproc: $(nproc --all)  OMP_NUM_THREADS: ${OMP_NUM_THREADS:-unset}  cpu: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')  commit: $(git rev-parse --short HEAD)"
echo "scenario: $scenario  checkpoint: $checkpoint  steps: $steps"
/usr/bin/python3 bench/ab_compare.py "$rounds" "$tmp/false.sh" "$tmp/true.sh" "$steps" 20 1 \
  --checkpoint "$checkpoint"
