#!/usr/bin/env bash
# Threads on a shared machine (issue 43, item 3): the step's rate with the thread count following
# the free cores (`auto`, rcdem run's default, core/thread_count_tuner.hpp) against fixed counts
# (every core, one and two fewer, 1 thread), on a quiet machine and with busy-loop processes
# holding one and two cores; then a run during which the neighbours come and go. Runs on the
# 2-core machine and on the lent 16-core one (bench/device_scaling.sh's companion).
#
# Usage: bash bench/shared_threads.sh OUT_DIR [BUILD_DIR=build]
#   1. header: date, nproc, CPU model, rcdem --version;
#   2. per load (0, 1, 2 busy processes; 2 only where nproc > 2), ROUNDS rounds of
#      rcdem_step_bench --threads auto,F (F: the free cores, the best fixed count; one process,
#      both counts from the same state, which must end on the same bits) on the 160 mm cube intact
#      (LONG_CUBE steps) and cracked (its tension checkpoint past the peak, made once at every
#      core; LONG_CRACK steps): what following the free cores costs against knowing them;
#   3. the same loads, a few steps (STEPS_CUBE, STEPS_CRACK) at --threads auto,N,N-1,N-2,1 (those
#      above 1): what too many threads cost (auto's rate here is mostly its first checks);
#   4. `rcdem run` of the tension cube (RUN_STEPS steps, no snapshots) at auto and at every core,
#      with one busy process started RUN_BUSY_AT seconds into the run and stopped RUN_BUSY_FOR
#      seconds later: the loop's rate from summary.json, and the count auto ended at.
#   Every result line is key=value; shared_threads.csv (one row per timed count) goes to OUT_DIR.
# Environment: ROUNDS (2), LONG_CUBE (8000), LONG_CRACK (3000), STEPS_CUBE (600), STEPS_CRACK
# (150), RUN_STEPS (6000), RUN_BUSY_AT (3), RUN_BUSY_FOR (6), SKIP_SHORT=1 (no section 3),
# QUICK=1 (a check of the script itself: few steps).
set -uo pipefail
cd "$(dirname "$0")/.."
OUT=${1:?usage: bash bench/shared_threads.sh OUT_DIR [BUILD_DIR]}
BUILD=${2:-build}
mkdir -p "$OUT"
LOG="$OUT/shared_threads.txt"
BENCH="$BUILD/bench/rcdem_step_bench"
NP=$(nproc --all)
ROUNDS=${ROUNDS:-2}
if [[ "${QUICK:-0}" == 1 ]]; then
  STEPS_CUBE=40 STEPS_CRACK=10 LONG_CUBE=80 LONG_CRACK=20 CRACK_AT=600 RUN_STEPS=300
  RUN_BUSY_AT=0.5 RUN_BUSY_FOR=1
else
  STEPS_CUBE=${STEPS_CUBE:-600} STEPS_CRACK=${STEPS_CRACK:-150} CRACK_AT=12000
  LONG_CUBE=${LONG_CUBE:-8000} LONG_CRACK=${LONG_CRACK:-3000}
  RUN_STEPS=${RUN_STEPS:-6000} RUN_BUSY_AT=${RUN_BUSY_AT:-3} RUN_BUSY_FOR=${RUN_BUSY_FOR:-6}
fi
COUNTS="auto,$NP"
for t in $((NP - 1)) $((NP - 2)); do ((t > 1)) && COUNTS+=",$t"; done
COUNTS+=",1"
WORK=$(mktemp -d)
trap 'kill $(jobs -p) 2>/dev/null; rm -rf "$WORK"' EXIT
say() { echo "$*" | tee -a "$LOG"; }
busy_start() { for ((b = 0; b < $1; ++b)); do (while :; do :; done) & done; sleep 0.5; }
busy_stop() { kill $(jobs -p) 2>/dev/null; wait 2>/dev/null; }

say "# bench/shared_threads.sh, $(date -u +%Y-%m-%dT%H:%M:%SZ)"
say "nproc=$NP cpu=\"$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//')\"" \
    "mem_GiB=$(awk '/MemTotal/ {printf "%.0f", $2/1048576}' /proc/meminfo)"
say "$("$BUILD/rcdem" --version 2>&1)"
say "counts=$COUNTS rounds=$ROUNDS steps_cube=$STEPS_CUBE steps_crack=$STEPS_CRACK"

CUBE=examples/uniaxial/compression.toml
TENSION=examples/uniaxial/tension.toml
OMP_NUM_THREADS=$NP "$BENCH" "$TENSION" 1 "$CRACK_AT" 1 --save-checkpoint "$WORK/crack" >/dev/null
CRACKED=$(ls "$WORK"/crack/checkpoint_*.h5 | tail -1)

LOADS="0 1"
((NP > 2)) && LOADS+=" 2"
# Per round and load, both states at the counts given: `free` is auto against the free cores.
time_loads() {  # RUN_NAME STEPS_CUBE STEPS_CRACK COUNTS
  local list
  for r in $(seq 1 "$ROUNDS"); do
    for busy in $LOADS; do
      busy_start "$busy"
      list=$4
      [[ $list == free ]] && list="auto,$((NP - busy > 1 ? NP - busy : 1))"
      for spec in "cube $CUBE $2 50" "cracked $TENSION $3 0 --checkpoint $CRACKED"; do
        read -r -a a <<< "$spec"
        OMP_NUM_THREADS=$NP "$BENCH" "${a[1]}" "${a[2]}" "${a[3]}" 1 "${a[@]:4}" --threads "$list" \
            2>&1 | grep -v '^# bytes' |
          sed "s/^/round=$r run=$1 busy_processes=$busy state=${a[0]} /" | tee -a "$LOG"
      done
      busy_stop
    done
  done
}

say "## the step over many steps: auto against the free cores (the best fixed count)"
time_loads long "$LONG_CUBE" "$LONG_CRACK" free

if [[ "${SKIP_SHORT:-0}" != 1 ]]; then
  say "## the step over a few steps: every core and fewer, fixed (and auto finding its count)"
  time_loads short "$STEPS_CUBE" "$STEPS_CRACK" "$COUNTS"
fi

say "## rcdem run: a neighbour comes ${RUN_BUSY_AT} s into the run and leaves ${RUN_BUSY_FOR} s later"
for threads in auto "$NP"; do
  rm -rf "$WORK/run"
  OMP_NUM_THREADS=$NP "$BUILD/rcdem" -q run "$TENSION" -o "$WORK/run" --threads "$threads" \
      --set stop.steps="$RUN_STEPS" --set output.snapshots=0 >/dev/null 2>&1 &
  pid=$!
  sleep "$RUN_BUSY_AT"
  (while :; do :; done) &
  neighbour=$!
  sleep "$RUN_BUSY_FOR"
  kill "$neighbour"
  wait "$pid"
  say "rcdem_run threads=$threads $(/usr/bin/env python3 -c 'import json,sys; s=json.load(open(sys.argv[1]));
t=s["threads"]; print("steps=%d loop_seconds=%.3f steps_per_s=%.2f threads_last=%d threads_mean=%.2f threads_changes=%d" % (s["steps"], s["loop_seconds"], s["steps_per_second"], t["last"], t["mean"], t["changes"]))' \
      "$WORK/run/summary.json" 2>&1)"
done

/usr/bin/env python3 - "$LOG" "$OUT/shared_threads.csv" <<'EOF'
import re, sys
with open(sys.argv[2], "w") as f:
    f.write("round,run,busy_processes,state,threads,threads_mean,threads_last,steps_per_s,"
            "end_strain_energy_J\n")
    for line in open(sys.argv[1]):
        if not line.startswith("round="):
            continue
        kv = dict(re.findall(r"(\w+)=(\S+)", line))
        f.write(",".join(kv[k] for k in ("round", "run", "busy_processes", "state", "threads",
                 "threads_mean", "threads_last", "steps_per_s", "end_strain_energy_J")) + "\n")
EOF
say "# done $(date -u +%Y-%m-%dT%H:%M:%SZ)"
