#!/bin/bash
# Issue 43 with 5dc20f2's step (the held contacts' data requested a block ahead, bench/RESULTS.md):
# YADE side by side, intact and cracked (bench/throughput.sh --cracked from the cube's checkpoint at
# step 12,000, made by e5c324e's step), 1 thread, in sequence (log: the .txt beside it), nothing
# else running. YADE: Debian's yade 2023.02a (apt-get install yade).
cd "$(dirname "$0")/../.."
date -u; nproc; grep -m1 "model name" /proc/cpuinfo; git log -1 --format=%h; build/rcdem --version
CK=${CK:-results/s54/ck_cube/checkpoint_000000012000.h5}
export OMP_NUM_THREADS=1
THREADS=1 RCDEM_THREADS=1 ROUNDS=3 REPEATS=2 CHECKPOINT=$CK bash bench/throughput.sh --cracked 200 2>&1 |
  grep -v "^$"
date -u
