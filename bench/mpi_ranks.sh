#!/usr/bin/env bash
# One process against two MPI ranks on one specimen (docs/parallel.md, issue 46 item 5): `rcdem run`
# of the `mpi` build for STEPS steps in alternating rounds of three set-ups: 1 process x 1 thread,
# 1 process x 2 threads, 2 ranks x 1 thread. Each run's loop time (summary.json loop_seconds: the
# steps alone, no generation) and, for the ranks, the share of rank 0's loop spent in exchanges
# (rank_0_exchange_seconds: the collectives and the waits for the other rank). Checks that the
# 2-rank history is the same bytes as the 1-process one.
#
# Usage: bash bench/mpi_ranks.sh SCENARIO [ROUNDS=2] [STEPS=1000] [BUILD=build-mpi]
#   e.g. bash bench/mpi_ranks.sh examples/three_point_bending/study/AN4_NL-B.toml 2 1000
# Prints one line per run and a table of medians: set-up, steps/s, ms/step, exchange share, the
# share of the local points rank 0 evaluates (its own and the cut's blocks).
set -euo pipefail
cd "$(dirname "$0")/.."
[[ $# -ge 1 ]] || { sed -n '2,11p' "$0" >&2; exit 2; }
scenario=$1
rounds=${2:-2}
steps=${3:-1000}
rcdem="$PWD/${4:-build-mpi}/rcdem"
[[ -x "$rcdem" ]] || { echo "missing $rcdem: cmake --preset mpi && cmake --build build-mpi --target rcdem" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
sets=(--set "stop.steps=$steps" --set output.snapshots=0 --set output.history_rows=10)
run() {  # name ranks threads
  local out="$tmp/$1_$4"
  if [[ $2 == 1 ]]; then
    OMP_NUM_THREADS=$3 "$rcdem" -q run "$scenario" -o "$out" --threads "$3" "${sets[@]}"
  else
    OMP_NUM_THREADS=$3 mpirun --allow-run-as-root --oversubscribe --bind-to none -np "$2" \
      "$rcdem" -q run "$scenario" -o "$out" --threads "$3" "${sets[@]}"
  fi
  /usr/bin/python3 - "$out/summary.json" "$1" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
d = s.get("distributed", {})
x = d.get("rank_0_exchange_seconds", 0.0)
points = d.get("rank_0_evaluated_points", s["local_points"]) / s["local_points"]
print(f"{sys.argv[2]} steps_per_second={s['steps'] / s['loop_seconds']:.3f} "
      f"exchange_share={x / s['loop_seconds']:.3f} rank0_points_share={points:.3f}")
PY
}
for r in $(seq 1 "$rounds"); do
  run 1x1 1 1 "$r"
  run 1x2 1 2 "$r"
  run 2x1 2 1 "$r"
  cmp -s "$tmp/1x1_$r/history.csv" "$tmp/2x1_$r/history.csv" ||
    { echo "round $r: the 2-rank history differs from the 1-process one" >&2; exit 1; }
done | tee "$tmp/lines"
/usr/bin/python3 - "$tmp/lines" <<'PY'
import statistics, sys
rows = {}
for line in open(sys.argv[1]):
    name, *kv = line.split()
    d = dict(x.split("=") for x in kv)
    rows.setdefault(name, []).append((float(d["steps_per_second"]), float(d["exchange_share"]),
                                      float(d["rank0_points_share"])))
print("| set-up | steps/s (median) | ms/step | exchange share of rank 0's loop "
      "| rank 0's share of the points |")
print("|---|---|---|---|---|")
for name in ("1x1", "1x2", "2x1"):
    sps = statistics.median(v[0] for v in rows[name])
    share = statistics.median(v[1] for v in rows[name])
    points = rows[name][0][2]
    label = {"1x1": "1 process x 1 thread", "1x2": "1 process x 2 threads",
             "2x1": "2 ranks x 1 thread"}[name]
    print(f"| {label} | {sps:.2f} | {1000 / sps:.1f} | {share:.1%} | {points:.1%} |")
PY
