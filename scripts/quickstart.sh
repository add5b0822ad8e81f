#!/usr/bin/env bash
# Sets up rcdem and runs the main job on the built-in example: the unreinforced AN0 beam of the
# paper's three-point bending study, generated with its VGCM-3D contact network.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
./build/rcdem generate examples/three_point_bending/AN0.toml -o results/AN0 --force
echo "Open results/AN0/particles.vtu and results/AN0/facets.vtu in ParaView; counts in results/AN0/summary.json"
