#!/usr/bin/env bash
# Sets up rcdem and runs the main job on the built-in example: the paper's three-point bending
# study on its unreinforced AN0 beam (quick variant: coarse particles, seconds), with the
# load-deflection curve, Table 3 row, crack pattern and deformed shape.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh rcdem   # the program alone: the tests, benchmarks and Python module are test.sh's
./build/rcdem study three_point_bending --quick --cases AN0 -o results/quick_study
echo "Study: results/quick_study/table3.md and figure*.png (the whole quick study: build/rcdem study three_point_bending --quick)"
echo "Next, the full-size AN0 specimen (the paper's particles, 26,500 of them, about 10 s):"
echo "  build/rcdem generate examples/three_point_bending/AN0.toml -o results/AN0   # then open results/AN0/*.vtu in ParaView"
