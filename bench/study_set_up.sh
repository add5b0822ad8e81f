#!/usr/bin/env bash
# Issue 26: the quick study at the set-up of an earlier commit (its scenario files, this binary)
# and at the current one, one after the other, and each case's steps and wall time.
#   bash bench/study_set_up.sh [OLD_COMMIT=24d55d6] [RCDEM=build/rcdem]
# Writes results/study_set_up/{before,after}/ (a second call reruns nothing already finished).
set -euo pipefail
cd "$(dirname "$0")/.."
OLD=${1:-24d55d6}
RCDEM=${2:-build/rcdem}
OUT=results/study_set_up
mkdir -p "$OUT/old_tree"
# The old scenarios at the same depth as in the repository, so their includes resolve.
git archive "$OLD" examples | tar -x -C "$OUT/old_tree"
run() {  # name, scenario directory
  local t0 t1
  t0=$(date +%s.%N)
  "$RCDEM" study three_point_bending --quick --scenarios "$2" -o "$OUT/$1" >"$OUT/$1.log" 2>&1
  t1=$(date +%s.%N)
  echo "$1: study wall time $(echo "$t1 - $t0" | bc) s" | tee -a "$OUT/times.txt"
}
[ -f "$OUT/before/done" ] || { run before "$OUT/old_tree/examples/three_point_bending/study/quick"; touch "$OUT/before/done"; }
[ -f "$OUT/after/done" ] || { run after examples/three_point_bending/study/quick; touch "$OUT/after/done"; }
/usr/bin/python3 - "$OUT" <<'PY'
import json, pathlib, sys
out = pathlib.Path(sys.argv[1])
print(f"{'case':12} {'steps before':>12} {'after':>8} {'ratio':>6} {'wall before':>11} {'after':>7} "
      f"{'peak before [kN]':>16} {'after':>7} {'diff':>6}")
for s in sorted((out / "before" / "cases").glob("*/summary.json")):
    a = out / "after" / "cases" / s.parent.name / "summary.json"
    if not a.exists():
        continue
    b, n = json.loads(s.read_text()), json.loads(a.read_text())
    print(f"{s.parent.name:12} {b['steps']:12d} {n['steps']:8d} {n['steps'] / b['steps']:6.3f} "
          f"{b['seconds']:11.1f} {n['seconds']:7.1f} {b['peak_load_N'] / 1e3:16.2f} "
          f"{n['peak_load_N'] / 1e3:7.2f} {100 * (n['peak_load_N'] / b['peak_load_N'] - 1):+5.1f}%")
PY
