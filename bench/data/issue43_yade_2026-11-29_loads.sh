#!/bin/bash
# Issue 43 after the held sums' loads (ceb49d4): YADE side by side, intact and cracked
# (bench/throughput.sh --cracked from the cube's checkpoint at step 12,000, made by 93c10b9, the
# same arithmetic), 1 thread, in sequence (log: the .txt beside it). The figure regeneration
# (nice 19) was paused with SIGSTOP for the whole script.
cd "$(dirname "$0")/../.."
date -u; nproc; grep -m1 "model name" /proc/cpuinfo; git log -1 --format=%h
CK=${CK:-results/s47/ck_cube/checkpoint_000000012000.h5}
export OMP_NUM_THREADS=1
THREADS=1 RCDEM_THREADS=1 ROUNDS=3 REPEATS=2 CHECKPOINT=$CK bash bench/throughput.sh --cracked 200 2>&1 |
  grep -v "^$"
date -u
