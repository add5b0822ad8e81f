#!/bin/bash
# Issue 43's measures on 40c7680's binaries (softening points held; 1 thread), in sequence (log:
# the .txt beside it). A = 8cfec46's rcdem_step_bench (the held contacts before, same step as
# 4a47aea), B = this tree's build/bench/rcdem_step_bench; /tmp/old551: 551b674's build.
# CK7: the cube at step 12,000 written by A (format 7: B restarts it with nothing held and holds
# again in its 20 warm-up steps); CK8: the same written by B (`rcdem_step_bench
# examples/uniaxial/tension.toml 1 12000 2 --save-checkpoint DIR`). CK4: 551b674's AN4 NL-B
# checkpoint at step 112,000 (format 5: nothing held for any of them).
cd /work/main
date -u; nproc; grep -m1 "model name" /proc/cpuinfo
A=results/s42/bin_broken; B=build/bench/rcdem_step_bench; OLD=/tmp/old551/build/bench/rcdem_step_bench
AN4=examples/three_point_bending/study/AN4_NL-B.toml; CK4=results/s42/an4_112000.rcp
CK7=results/s42/ckpt_tension8/checkpoint_000000012000.h5
CK8=results/s43/ckpt_tension_soft/checkpoint_000000012000.h5
echo "== cube from CK7: 8cfec46 vs 40c7680"
OMP_NUM_THREADS=1 python3 bench/ab_compare.py 8 $A $B examples/uniaxial/tension.toml 300 20 1 --checkpoint $CK7
echo "== AN4 NL-B at step 112,000: 8cfec46 vs 40c7680"
OMP_NUM_THREADS=1 python3 bench/ab_compare.py 6 $A $B $AN4 100 50 1 --checkpoint $CK4
echo "== AN4 NL-B at step 112,000: 551b674 vs 40c7680"
OMP_NUM_THREADS=1 python3 bench/ab_compare.py 6 $OLD $B $AN4 100 50 1 --checkpoint $CK4
echo "== cracked / intact pairs (B, its own checkpoint)"
for r in 1 2 3; do
  i=$(OMP_NUM_THREADS=1 $B examples/uniaxial/tension.toml 1000 50 1 | grep -o "steps_per_s=[0-9.]*" | head -1)
  c=$(OMP_NUM_THREADS=1 $B examples/uniaxial/tension.toml 300 20 1 --checkpoint $CK8 | grep -o "steps_per_s=[0-9.]*" | head -1)
  echo "pair $r intact $i cracked $c"
done
echo "== YADE side by side"
THREADS=1 ROUNDS=3 REPEATS=2 CHECKPOINT=$CK8 bash bench/throughput.sh --cracked 200
date -u
