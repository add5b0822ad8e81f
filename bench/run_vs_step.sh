#!/usr/bin/env bash
# What a run costs around its step (issue 43, item 2): `rcdem run` of a scenario's first STEPS
# steps (the loop's rate from summary.json: history rows, crack record, stop rules, progress),
# against `rcdem_step_bench` on the same STEPS steps from the same start (the step alone), in
# alternating rounds, at the thread count OMP_NUM_THREADS gives (default 1).
#
# Usage: bash bench/run_vs_step.sh SCENARIO STEPS [ROUNDS=3] [BUILD=build]
#   The run writes no snapshots (output.snapshots = 0: writing VTU files is output, not the
#   run's bookkeeping); its history has one row per step (a run of STEPS steps spreads
#   output.history_rows = 2,000 rows over them) unless HISTORY_ROWS sets fewer.
# Environment: OMP_NUM_THREADS (1), HISTORY_ROWS, PY (/usr/bin/python3).
# Prints one line per round (run and step rates, their ratio, and around_steps_share: the share of
# the run's loop spent around its steps, 1 - step_seconds / loop_seconds of its summary.json,
# measured inside the one run and so free of the rounds' load changes) and last lines
#   run_over_step_median=<median of the rounds' ratios>
#   around_steps_share_median=<median of the rounds' shares>
set -euo pipefail
cd "$(dirname "$0")/.."
SCENARIO=${1:?usage: bash bench/run_vs_step.sh SCENARIO STEPS [ROUNDS] [BUILD]}
STEPS=${2:?usage: bash bench/run_vs_step.sh SCENARIO STEPS [ROUNDS] [BUILD]}
ROUNDS=${3:-3}
BUILD=${4:-build}
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-1}
PY=${PY:-/usr/bin/python3}  # Debian's; another where it is elsewhere (PY=python3)
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
# A fixed count, as the step bench's: the run's bookkeeping, not its thread tuning, is measured.
sets=(--set stop.steps="$STEPS" --set output.snapshots=0 --threads "$OMP_NUM_THREADS")
[[ -n "${HISTORY_ROWS:-}" ]] && sets+=(--set output.history_rows="$HISTORY_ROWS")
echo "# bench/run_vs_step.sh $SCENARIO $STEPS, $(date -u +%Y-%m-%dT%H:%M:%SZ), nproc $(nproc --all)," \
     "\"$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//')\"," \
     "threads $OMP_NUM_THREADS, $("$BUILD/rcdem" --version)"
ratios=()
shares=()
for ((r = 1; r <= ROUNDS; ++r)); do
  rm -rf "$WORK/run"
  "$BUILD/rcdem" -q run "$SCENARIO" -o "$WORK/run" "${sets[@]}" >/dev/null
  read -r run around < <("$PY" -c 'import json,sys; s=json.load(open(sys.argv[1]));
print(s["steps_per_second"], 1.0 - s["step_seconds"] / s["loop_seconds"])' "$WORK/run/summary.json")
  rows=$(($(wc -l < "$WORK/run/history.csv") - 1))
  step=$("$BUILD/bench/rcdem_step_bench" "$SCENARIO" "$STEPS" 0 1 | grep -o ' steps_per_s=[0-9.]*' |
         cut -d= -f2)
  ratio=$("$PY" -c "print(f'{$run / $step:.3f}')")
  ratios+=("$ratio")
  shares+=("$around")
  echo "round=$r run_steps_per_s=$(printf %.1f "$run") around_steps_share=$(printf %.4f "$around")" \
       "history_rows=$rows" \
       "step_steps_per_s=$(printf %.1f "$step") run_over_step=$ratio"
done
echo "run_over_step_median=$(printf '%s\n' "${ratios[@]}" | sort -g |
  "$PY" -c 'import sys, statistics; print(statistics.median(float(x) for x in sys.stdin))')"
echo "around_steps_share_median=$(printf '%s\n' "${shares[@]}" | sort -g |
  "$PY" -c 'import sys, statistics; print(f"{statistics.median(float(x) for x in sys.stdin):.4f}")')"
