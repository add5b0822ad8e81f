#!/usr/bin/env bash
# Sets up rcdem and runs the main job on the built-in example: the paper's three-point bending
# study on its unreinforced AN0 beam (quick variant: coarse particles, a few minutes), with the
# load-deflection curve, Table 3 row, crack pattern and deformed shape; then the full-size AN0
# specimen is generated with its VGCM-3D contact network.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh rcdem   # the program alone: the tests, benchmarks and Python module are test.sh's
./build/rcdem study three_point_bending --quick --cases AN0 -o results/quick_study
./build/rcdem generate examples/three_point_bending/AN0.toml -o results/AN0 --force
echo "Study: results/quick_study/table3.md and figure*.png (the whole quick study: rcdem study three_point_bending --quick)"
echo "Full-size AN0 specimen: open results/AN0/particles.vtu and facets.vtu in ParaView; counts in results/AN0/summary.json"
