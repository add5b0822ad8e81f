#!/bin/bash
# Idle-thread waiting on a quiet and a loaded machine (bench/RESULTS.md, "Threads on a shared
# machine"): rcdem_step_bench on the intact 160 mm cube, per round 2 threads spinning
# (OMP_WAIT_POLICY=active), 2 threads passive and 1 thread; four rounds quiet, then four with one
# busy-loop process holding a core. Prints each run's steps/s.
# Usage: bash bench/wait_policy.sh [BENCH_BINARY]   (from the repository root)
set -euo pipefail
B=${1:-build/bench/rcdem_step_bench}
S=examples/uniaxial/compression.toml
run() { OMP_NUM_THREADS=$1 OMP_WAIT_POLICY=$2 "$B" "$S" 1500 50 1 | grep -o "\bsteps_per_s=[0-9.]*" | head -1 | cut -d= -f2; }
for load in quiet busy; do
  busy=""
  if [ "$load" = busy ]; then (while :; do :; done) & busy=$!; fi
  for r in 1 2 3 4; do
    echo "$load round $r: 2T active $(run 2 active)  2T passive $(run 2 passive)  1T $(run 1 passive)"
  done
  [ -n "$busy" ] && kill "$busy"
done
