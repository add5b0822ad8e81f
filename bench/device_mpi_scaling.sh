#!/usr/bin/env bash
# Strong scaling of the distributed run on a many-core machine (issue 46 item 5): the 16-core
# machine a session is sometimes lent for a few minutes. One short script, so that the lease is
# spent measuring; every result is written to OUT_DIR as it comes (a run cut short keeps them).
#
# Usage: bash bench/device_mpi_scaling.sh OUT_DIR RCDEM [MPIRUN=mpirun]
#   RCDEM: an `mpi` build of rcdem (cmake --preset mpi); MPIRUN: Open MPI's launcher. To carry
#   both to a machine without Open MPI: bash bench/device_bundle.sh (it prints the command).
#   1. header: date, nproc, CPU, memory, rcdem --version, the launcher's version;
#   2. the full AN4 NL-B beam, `rcdem run` for STEPS_AN4 steps, ROUNDS rounds of every set-up in
#      CONFIGS_AN4 (RANKSxTHREADS; 1xT runs without the launcher);
#   3. the 400 mm beam of the size series at full resolution, STEPS_H400 steps, once per set-up in
#      CONFIGS_H400, set-ups whose ranks would not fit in memory (MEM_PER_RANK_GIB each) skipped.
#      Its packing is relaxed RELAX_H400 iterations instead of 300: every rank generates the whole
#      specimen, and the full relaxation on one thread would take most of the lease; the step's
#      cost follows the particle, contact and point counts, which are reported.
#   Per run: the loop's steps/s (summary.json loop_seconds: the steps alone), the set-up's seconds
#   (generation, tessellation, time step), rank 0's share of the loop spent in exchanges and of
#   the local points it evaluates, the machine's peak memory in use (MemAvailable sampled every
#   0.5 s), and whether history.csv is the same bytes as the specimen's first set-up's; every
#   rank's exchange share (the least waiting rank is the one the others wait for) and rank 0's by
#   kind (command, dissipation, crack_log, spheres, requests). A set-up
#   that would start after DEADLINE_S seconds of the script is skipped (default 450).
#   Output: OUT_DIR/device_mpi_scaling.txt (key=value lines) and mpi_scaling.csv.
set -uo pipefail
cd "$(dirname "$0")/.."
OUT=${1:?usage: bash bench/device_mpi_scaling.sh OUT_DIR RCDEM [MPIRUN]}
RCDEM=$(realpath "${2:?usage: bash bench/device_mpi_scaling.sh OUT_DIR RCDEM [MPIRUN]}")
MPIRUN=${3:-mpirun}
CONFIGS_AN4=${CONFIGS_AN4:-"1x1 2x1 4x1 8x1 16x1 1x16 2x8 4x4 8x2"}
CONFIGS_H400=${CONFIGS_H400:-"1x16 8x2 1x1 4x4 2x8 16x1"}
ROUNDS=${ROUNDS:-2}
STEPS_AN4=${STEPS_AN4:-600}
STEPS_H400=${STEPS_H400:-100}
RELAX_H400=${RELAX_H400:-30}
MEM_PER_RANK_GIB=${MEM_PER_RANK_GIB:-8}
DEADLINE_S=${DEADLINE_S:-450}
mkdir -p "$OUT"
LOG="$OUT/device_mpi_scaling.txt"
CSV="$OUT/mpi_scaling.csv"
WORK=$(mktemp -d)
trap 'kill $(jobs -p) 2>/dev/null; rm -rf "$WORK"' EXIT
START=$(date +%s)
say() { echo "$*" | tee -a "$LOG"; }
mem_kib() { awk '/MemAvailable/ {print $2}' /proc/meminfo; }
TOTAL_KIB=$(awk '/MemTotal/ {print $2}' /proc/meminfo)

say "# bench/device_mpi_scaling.sh, $(date -u +%Y-%m-%dT%H:%M:%SZ)"
say "nproc=$(nproc) cpu=\"$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//')\"" \
    "sockets=$(grep 'physical id' /proc/cpuinfo | sort -u | wc -l)" \
    "mem_GiB=$((TOTAL_KIB / 1048576))"
say "$("$RCDEM" --version 2>&1 | head -1)"
say "launcher: $("$MPIRUN" --version 2>&1 | head -1)"
echo "specimen,round,ranks,threads,steps,steps_per_s,setup_s,exchange_share,rank0_points_share,peak_mem_GiB,same_history,least_waiting_rank_share,most_waiting_rank_share,rank0_kinds" > "$CSV"

# run NAME SCENARIO RANKS THREADS ROUND STEPS [--set ...]: one run, one result line.
run() {
  local name=$1 scenario=$2 ranks=$3 threads=$4 round=$5 steps=$6
  shift 6
  local out="$WORK/${name}_${ranks}x${threads}_$round"
  local elapsed=$(($(date +%s) - START))
  if ((elapsed > DEADLINE_S)); then say "skipped specimen=$name ranks=$ranks threads=$threads (past the deadline)"; return; fi
  if ((ranks * MEM_PER_RANK_GIB * 1048576 > TOTAL_KIB * 9 / 10)) && [[ $name == h400 ]]; then
    say "skipped specimen=$name ranks=$ranks threads=$threads (memory: $ranks x $MEM_PER_RANK_GIB GiB)"; return
  fi
  local base mem
  base=$(mem_kib)
  (low=$base; while :; do m=$(mem_kib); ((m < low)) && low=$m && echo "$low" > "$WORK/low"; sleep 0.5; done) &
  local sampler=$!
  echo "$base" > "$WORK/low"
  local cmd=("$RCDEM" -q run "$scenario" -o "$out" --threads "$threads" --set "stop.steps=$steps"
             --set output.snapshots=0 --set output.history_rows=10 --checkpoint-every 0 "$@")
  if ((ranks == 1)); then
    OMP_NUM_THREADS=$threads timeout 400 "${cmd[@]}" > "$WORK/run.log" 2>&1
  else
    OMP_NUM_THREADS=$threads timeout 400 "$MPIRUN" --allow-run-as-root --oversubscribe \
      --bind-to none -np "$ranks" "${cmd[@]}" > "$WORK/run.log" 2>&1
  fi
  local rc=$?
  kill "$sampler" 2>/dev/null; wait "$sampler" 2>/dev/null
  mem=$(( (base - $(cat "$WORK/low")) ))
  if [[ $rc != 0 || ! -f "$out/summary.json" ]]; then
    say "failed specimen=$name ranks=$ranks threads=$threads rc=$rc: $(tail -3 "$WORK/run.log" | tr '\n' ' ')"
    return
  fi
  local first="$WORK/first_$name.csv" same=first
  if [[ -f "$first" ]]; then cmp -s "$first" "$out/history.csv" && same=yes || same=NO
  else cp "$out/history.csv" "$first"; fi
  /usr/bin/env python3 - "$out/summary.json" "$name" "$round" "$ranks" "$threads" "$mem" "$same" \
      "$CSV" <<'PY' | tee -a "$LOG"
import json, sys
s = json.load(open(sys.argv[1]))
name, rnd, ranks, threads, mem_kib, same, csv = sys.argv[2:]
d = s.get("distributed", {})
loop = s["loop_seconds"]
sps = s["steps"] / loop
setup = s["seconds"] - loop
x = d.get("rank_0_exchange_seconds", 0.0) / loop
pts = d.get("rank_0_evaluated_points", s["local_points"]) / s["local_points"]
mem = int(mem_kib) / 1048576
# Every rank's exchange share (summary.json's exchange_seconds_by_rank): the rank that waits least is the one
# the others wait for; rank 0's by kind says where its share goes.
by_rank = [sum(r.values()) / loop for r in d.get("exchange_seconds_by_rank", [])]
least = min(by_rank) if by_rank else 0.0
most = max(by_rank) if by_rank else 0.0
kinds = ";".join(f"{k}:{v / loop:.3f}" for k, v in d.get("exchange_seconds_by_rank", [{}])[0].items())
print(f"specimen={name} round={rnd} ranks={ranks} threads={threads} steps={s['steps']} "
      f"steps_per_s={sps:.2f} setup_s={setup:.1f} exchange_share={x:.3f} "
      f"rank0_points_share={pts:.3f} peak_mem_GiB={mem:.1f} same_history={same} "
      f"local_points={s['local_points']} particles={s['specimen'].get('particles', {}).get('total', '')} "
      f"least_waiting_rank_share={least:.3f} most_waiting_rank_share={most:.3f} rank0_kinds={kinds}")
with open(csv, "a") as f:
    f.write(f"{name},{rnd},{ranks},{threads},{s['steps']},{sps:.3f},{setup:.2f},{x:.4f},"
            f"{pts:.4f},{mem:.2f},{same},{least:.4f},{most:.4f},{kinds}\n")
PY
  rm -rf "$out"
}

say "## AN4 NL-B beam, full resolution, $STEPS_AN4 steps, $ROUNDS rounds"
for r in $(seq 1 "$ROUNDS"); do
  for c in $CONFIGS_AN4; do
    run AN4 examples/three_point_bending/study/AN4_NL-B.toml "${c%x*}" "${c#*x}" "$r" "$STEPS_AN4"
  done
done
say "## 400 mm beam (1.05%), full resolution, $STEPS_H400 steps, relaxation $RELAX_H400 iterations"
for c in $CONFIGS_H400; do
  run h400 examples/size_series/study/h400_rho1.05.toml "${c%x*}" "${c#*x}" 1 "$STEPS_H400" \
      --set "generation.relaxation_iterations=$RELAX_H400"
done
say "# done $(date -u +%Y-%m-%dT%H:%M:%SZ), $(($(date +%s) - START)) s"
