#!/usr/bin/env bash
# Solver throughput on the 160 mm cube (issue 3): steps/s, particle-, contact- and local-point-
# steps/s at 1 and 2 threads, over K steps of uniaxial compression with Table 2's BL law (the step
# loop only: generation excluded; history and snapshots nearly off).
# Usage: bash bench/solver_throughput.sh [STEPS=2000] [BUILD_DIR=build]
set -euo pipefail
cd "$(dirname "$0")/.."
K=${1:-2000}
BIN=${2:-build}/rcdem
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
sed -e "s/^load_drop = .*//" -e "s/^displacement = .*/steps = $K/" -e "s/^snapshots = .*/snapshots = 0\nhistory_rows = 10/" \
  examples/uniaxial/compression.toml > "$tmp/bench.toml"
echo "date: $(date -u +%Y-%m-%d)  nproc: $(nproc)  cpu: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')  steps: $K"
for t in 1 2; do
  OMP_NUM_THREADS=$t "$BIN" --quiet run "$tmp/bench.toml" -o "$tmp/t$t" --force
  /usr/bin/python3 - "$tmp/t$t/summary.json" "$t" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
sp = s["specimen"]
rate = s["steps_per_second"]
print(f"threads {sys.argv[2]}: {rate:.1f} steps/s; particle-steps/s {rate * sp['particles']['total']:.3g}; "
      f"contact-steps/s {rate * sp['contacts']:.3g}; local-point-steps/s {rate * sp['local_points']:.3g} "
      f"({sp['particles']['total']} particles, {sp['contacts']} contacts, {sp['local_points']} local points)")
PY
done
