#!/usr/bin/env bash
# Two `mpi` builds of rcdem on the same distributed run, in alternating rounds (this machine is
# shared and noisy: a change is judged only against the other build in the same rounds):
# `mpirun -np RANKS rcdem run SCENARIO` for STEPS steps, 1 thread per rank; per run the loop's
# steps/s (summary.json loop_seconds) and rank 0's share of it in exchanges. Checks that both
# builds write the same history.csv.
#
# Usage: bash bench/mpi_ab.sh OLD_RCDEM NEW_RCDEM SCENARIO [ROUNDS=3] [STEPS=1000] [RANKS=2]
#   e.g. bash bench/mpi_ab.sh /tmp/rcdem_old build-mpi/rcdem \
#          examples/three_point_bending/study/AN4_NL-B.toml 3 1000 2
set -euo pipefail
cd "$(dirname "$0")/.."
[[ $# -ge 3 ]] || { sed -n '2,10p' "$0" >&2; exit 2; }
old=$(realpath "$1") new=$(realpath "$2") scenario=$3
rounds=${4:-3} steps=${5:-1000} ranks=${6:-2}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for r in $(seq 1 "$rounds"); do
  for which in old new; do
    bin=$old
    [[ $which == new ]] && bin=$new
    OMP_NUM_THREADS=1 mpirun --allow-run-as-root --oversubscribe --bind-to none -np "$ranks" \
      "$bin" -q run "$scenario" -o "$tmp/$which" --force --threads 1 --set "stop.steps=$steps" \
      --set output.snapshots=0 --set output.history_rows=10
    /usr/bin/python3 - "$tmp/$which/summary.json" "$which" "$r" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
x = s["distributed"]["rank_0_exchange_seconds"] / s["loop_seconds"]
print(f"round={sys.argv[3]} build={sys.argv[2]} steps_per_s={s['steps'] / s['loop_seconds']:.1f} "
      f"exchange_share={x:.3f}")
PY
  done
  cmp -s "$tmp/old/history.csv" "$tmp/new/history.csv" ||
    { echo "round $r: the two builds' histories differ" >&2; exit 1; }
done
echo "histories: the same bytes in every round"
