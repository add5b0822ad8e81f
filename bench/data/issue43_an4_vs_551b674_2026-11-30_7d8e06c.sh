#!/bin/bash
# Issue 43's yardstick: the cracked AN4 NL-B step against HEAD 551b674's, 1 thread, alternating
# rounds (log: the .txt beside it). OLD = 551b674's rcdem_step_bench (a worktree: `git worktree add
# /tmp/old551 551b674`, `cmake -S /tmp/old551 -B /tmp/old551/build -G Ninja
# -DCMAKE_BUILD_TYPE=Release -DRCDEM_BUILD_TESTS=OFF`), NEW = this commit's build/bench/rcdem_step_bench (7d8e06c's step)
# (2 MiB pages). The checkpoint: 551b674's own run of this scenario, `OMP_NUM_THREADS=2
# /tmp/old551/build/rcdem run examples/three_point_bending/study/AN4_NL-B.toml -o
# results/s54/an4_551run --checkpoint-every 112000`, stopped after its checkpoint at step 112,000
# (35.3 kN; 551b674's step bench cannot save one).
cd "$(dirname "$0")/../.."
date -u; nproc; grep -m1 "model name" /proc/cpuinfo; git log -1 --format=%h
OLD=${OLD:-/tmp/old551/build/bench/rcdem_step_bench}; NEW=build/bench/rcdem_step_bench
CK=${CK:-results/s54/an4_551run/checkpoint_000000112000.rcp}
export OMP_NUM_THREADS=1
/usr/bin/python3 bench/ab_compare.py 8 $OLD $NEW examples/three_point_bending/study/AN4_NL-B.toml \
  100 50 1 --checkpoint $CK
date -u
