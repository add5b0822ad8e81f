#!/usr/bin/env bash
# Thread scaling of the step on a many-core machine: the 16-core machine a session is sometimes
# lent for a few minutes (issue 43 item 3: threads that share a machine; issue 46 item 5: scaling
# evidence, before MPI exists). One short script, so that a lease of minutes is spent measuring.
#
# Usage: bash bench/device_scaling.sh OUT_DIR [BUILD_DIR=build]
#   1. header: date, nproc, CPU model, sockets and NUMA nodes, rcdem --version;
#   2. STREAM triad (bench/stream_triad.cpp) at 1 thread and at every core;
#   3. strong scaling of the step (rcdem_step_bench --threads: one generation per specimen, every
#      thread count from the same state, which must end on the same bits), REPEATS repetitions,
#      the fastest reported: the 160 mm cube intact (10k particles); the same cube cracked (pulled
#      in tension 12,000 steps, past its peak: the state is made once, at every core, and saved);
#      the AN4 NL-B beam intact (26k bodies); a 350 mm cube intact (108k particles);
#   4. a shared machine: the intact and cracked cubes (a third and half of section 3's steps, 2
#      repetitions) at every core, every core but one, and 1 thread, with one and with two
#      busy-loop processes beside them, rcdem's default waiting (passive) and
#      OMP_WAIT_POLICY=active;
#   5. the run's bookkeeping: `rcdem run` of the tension cube for 1,500 steps (its default history
#      density) against rcdem_step_bench's same 1,500 steps, at 1 thread and at every core.
#   Every result line is key=value; a summary table (scaling.csv) is written to OUT_DIR.
# Environment: THREADS_LIST (default 1,2,4,8,16, capped at nproc), REPEATS (3), SKIP_BIG=1 (no
# 350 mm cube), QUICK=1 (a check of the script itself: few steps, small warm-ups).
set -uo pipefail
cd "$(dirname "$0")/.."
OUT=${1:?usage: bash bench/device_scaling.sh OUT_DIR [BUILD_DIR]}
BUILD=${2:-build}
mkdir -p "$OUT"
LOG="$OUT/device_scaling.txt"
BENCH="$BUILD/bench/rcdem_step_bench"
NP=$(nproc)
REPEATS=${REPEATS:-3}
if [[ -z "${THREADS_LIST:-}" ]]; then
  THREADS_LIST=""
  for t in 1 2 4 8 16 32 64; do ((t <= NP)) && THREADS_LIST+="${THREADS_LIST:+,}$t"; done
  [[ ",$THREADS_LIST," == *",$NP,"* ]] || THREADS_LIST+=",$NP"
fi
if [[ "${QUICK:-0}" == 1 ]]; then S_CUBE=20 S_CRACK=10 S_BEAM=10 S_BIG=5 CRACK_AT=600 RUN_STEPS=200
else S_CUBE=300 S_CRACK=100 S_BEAM=200 S_BIG=50 CRACK_AT=12000 RUN_STEPS=1500; fi
WORK=$(mktemp -d)
trap 'kill $(jobs -p) 2>/dev/null; rm -rf "$WORK"' EXIT
say() { echo "$*" | tee -a "$LOG"; }
# Result lines only (the "# bytes:" lines go to the log too, not to the screen).
bench() { "$BENCH" "$@" 2>&1 | tee -a "$LOG" | grep -v '^# bytes' ; }

say "# bench/device_scaling.sh, $(date -u +%Y-%m-%dT%H:%M:%SZ)"
say "nproc=$NP cpu=\"$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//')\"" \
    "sockets=$(grep 'physical id' /proc/cpuinfo | sort -u | wc -l)" \
    "numa_nodes=$(ls -d /sys/devices/system/node/node* 2>/dev/null | wc -l)" \
    "mem_GiB=$(awk '/MemTotal/ {printf "%.0f", $2/1048576}' /proc/meminfo)"
say "$("$BUILD/rcdem" --version 2>&1)"
say "threads_list=$THREADS_LIST repeats=$REPEATS"

say "## STREAM triad"
for t in 1 "$NP"; do say "threads=$t $(OMP_NUM_THREADS=$t "$BUILD/bench/rcdem_stream" 2>&1)"; done

say "## strong scaling of the step"
CUBE=examples/uniaxial/compression.toml
TENSION=examples/uniaxial/tension.toml
BEAM=examples/three_point_bending/study/AN4_NL-B.toml
bench "$CUBE" "$S_CUBE" 50 "$REPEATS" --threads "$THREADS_LIST"
OMP_NUM_THREADS=$NP "$BENCH" "$TENSION" 1 "$CRACK_AT" 1 --save-checkpoint "$WORK/crack" >/dev/null
CRACKED=$(ls "$WORK"/crack/checkpoint_*.h5 | tail -1)
bench "$TENSION" "$S_CRACK" 0 "$REPEATS" --checkpoint "$CRACKED" --threads "$THREADS_LIST"
bench "$BEAM" "$S_BEAM" 20 "$REPEATS" --threads "$THREADS_LIST"
if [[ "${SKIP_BIG:-0}" != 1 ]]; then
  sed -e 's/^size = .*/size = [0.35, 0.35, 0.35]/' "$CUBE" > "$WORK/cube_350mm.toml"
  bench "$WORK/cube_350mm.toml" "$S_BIG" 10 "$REPEATS" --threads "$THREADS_LIST"
fi

say "## a shared machine: busy-loop processes beside rcdem"
SHARED_LIST="$NP,$((NP - 1)),1"
for busy in 1 2; do
  for policy in default active; do
    for ((b = 0; b < busy; ++b)); do (while :; do :; done) & done
    sleep 0.5
    env_policy=()
    [[ $policy == active ]] && env_policy=(OMP_WAIT_POLICY=active)
    # A third of the steps, 2 repetitions: a starved step can be 10-20x slower.
    for spec in "$CUBE $((S_CUBE / 3)) 50" "$TENSION $((S_CRACK / 2)) 0 --checkpoint $CRACKED"; do
      read -r -a a <<< "$spec"
      env "${env_policy[@]}" "$BENCH" "${a[0]}" "${a[1]}" "${a[2]}" 2 "${a[@]:3}" \
          --threads "$SHARED_LIST" 2>&1 | grep -v '^# bytes' |
        sed "s/^/busy_processes=$busy wait_policy=$policy /" | tee -a "$LOG"
    done
    kill $(jobs -p) 2>/dev/null
    wait 2>/dev/null
  done
done

say "## the run's bookkeeping: rcdem run against the step alone ($RUN_STEPS steps)"
for t in 1 "$NP"; do
  rm -rf "$WORK/run_$t"
  OMP_NUM_THREADS=$t "$BUILD/rcdem" -q run "$TENSION" -o "$WORK/run_$t" \
      --set stop.steps="$RUN_STEPS" --set output.snapshots=0 >/dev/null 2>&1
  say "rcdem_run threads=$t $(/usr/bin/env python3 -c 'import json,sys; s=json.load(open(sys.argv[1]));
print("steps=%d loop_seconds=%.4f steps_per_s=%.3f" % (s["steps"], s["loop_seconds"], s["steps_per_second"]))' \
      "$WORK/run_$t/summary.json" 2>&1)"
  OMP_NUM_THREADS=$t "$BENCH" "$TENSION" "$RUN_STEPS" 0 1 2>&1 | grep -v '^# bytes' |
    sed 's/^/step_bench /' | tee -a "$LOG"
done

# The summary table: one row per result line of sections 3 and 4.
/usr/bin/env python3 - "$LOG" "$OUT/scaling.csv" <<'EOF'
import re, sys
rows = []
for line in open(sys.argv[1]):
    if "steps_per_s=" not in line or line.startswith(("rcdem_run", "step_bench")):
        continue
    kv = dict(re.findall(r"(\w+)=(\S+)", line))
    rows.append([kv.get("busy_processes", "0"), kv.get("wait_policy", "default"),
                 kv["scenario"].split("/")[-1], kv["bodies"], kv["threads"], kv["steps_per_s"],
                 kv["particle_steps_per_s"], kv["condensed_contacts"], kv["end_strain_energy_J"]])
with open(sys.argv[2], "w") as f:
    f.write("busy_processes,wait_policy,scenario,bodies,threads,steps_per_s,particle_steps_per_s,"
            "condensed_contacts,end_strain_energy_J\n")
    for r in rows:
        f.write(",".join(r) + "\n")
EOF
say "# done $(date -u +%Y-%m-%dT%H:%M:%SZ)"
