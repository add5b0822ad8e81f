#!/usr/bin/env bash
# Sets up (scripts/setup.sh), builds, and runs every test: unit, verification and regression.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive} ctest --test-dir "${BUILD_DIR:-build}" --output-on-failure -j "$(nproc)" "$@"
