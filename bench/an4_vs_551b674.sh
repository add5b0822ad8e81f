#!/usr/bin/env bash
# Issue 43's yardstick: the cracked AN4 NL-B step of this checkout's build against HEAD 551b674's,
# 1 thread, 8 alternating rounds (bench/ab_compare.py), 100 steps after 50 from 551b674's own
# checkpoint at step 112,000 (35.3 kN). Prints the date, nproc, the CPU and this commit first, so
# that a log names what it measured.
#
# OLD: 551b674's rcdem_step_bench, built in a worktree:
#   git worktree add /tmp/old551 551b674 &&
#   cmake -S /tmp/old551 -B /tmp/old551/build -G Ninja -DCMAKE_BUILD_TYPE=Release -DRCDEM_BUILD_TESTS=OFF &&
#   ninja -C /tmp/old551/build rcdem rcdem_step_bench
# CK: that checkpoint (551b674's step bench cannot save one), from 551b674's own run, stopped after it:
#   OMP_NUM_THREADS=2 /tmp/old551/build/rcdem run examples/three_point_bending/study/AN4_NL-B.toml \
#     -o results/s54/an4_551run --checkpoint-every 112000
# NEW: build/bench/rcdem_step_bench (ninja -C build rcdem_step_bench).
set -euo pipefail
cd "$(dirname "$0")/.."
date -u; nproc; grep -m1 "model name" /proc/cpuinfo; git log -1 --format=%h
OLD=${OLD:-/tmp/old551/build/bench/rcdem_step_bench}; NEW=build/bench/rcdem_step_bench
CK=${CK:-results/s54/an4_551run/checkpoint_000000112000.rcp}
export OMP_NUM_THREADS=1
/usr/bin/python3 bench/ab_compare.py 8 "$OLD" "$NEW" examples/three_point_bending/study/AN4_NL-B.toml \
  100 50 1 --checkpoint "$CK"
date -u
