#!/usr/bin/env bash
# Times `rcdem generate` on the AN0 beam (and the 160 mm cube) with peak memory, and prints the
# machine it ran on. Usage: bash bench/generate_an0.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=${1:-build}/rcdem
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "date: $(date -u +%Y-%m-%d)  nproc: $(nproc)  cpu: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
for scen in examples/three_point_bending/AN0.toml examples/uniaxial/cube160.toml; do
  name=$(basename "$scen" .toml)
  /usr/bin/time -v "$BIN" --quiet generate "$scen" -o "$out/$name" 2> "$out/$name.time"
  wall=$(grep "Elapsed (wall clock)" "$out/$name.time" | awk '{print $NF}')
  rss=$(grep "Maximum resident set size" "$out/$name.time" | awk '{print $NF}')
  /usr/bin/python3 - "$out/$name/summary.json" "$name" "$wall" "$rss" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
p = s["particles"]
print(f"{sys.argv[2]}: {p['aggregate']} aggregate + {p['mortar']} mortar + {p['steel']} steel = {p['total']}; "
      f"{s['contacts']} contacts ({s['contacts_per_particle']:.2f}/particle); {s['local_points']} local points "
      f"({s['local_points_per_contact']:.2f}/contact); porosity {s['porosity']:.4f}; "
      f"wall {sys.argv[3]} (internal {s['seconds']:.2f} s); peak RSS {int(sys.argv[4]) / 1024:.0f} MiB")
PY
done
