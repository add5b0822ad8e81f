#!/bin/bash
# Issue 43's measures on 8cfec46's binaries (1 thread), in sequence (log: the .txt beside it).
# A = aebe20d's rcdem_step_bench (a worktree build, `cmake -S . -B build -G Ninja
#   -DCMAKE_BUILD_TYPE=Release -DRCDEM_BUILD_TESTS=OFF && ninja -C build rcdem_step_bench`), B = 8cfec46's.
# /tmp/old551: 551b674's build (as in issue43_measures_2026-11-28_rowwise.sh); an4_112000.rcp its
#   AN4 NL-B checkpoint at step 112,000; ckpt_tension: the cube's at step 12,000 made by B
#   (`rcdem_step_bench examples/uniaxial/tension.toml 1 12000 1 --save-checkpoint DIR`).
cd /work/main
date -u; nproc; grep -m1 "model name" /proc/cpuinfo
A=results/s42/bin_aebe20d; B=build/bench/rcdem_step_bench; OLD=/tmp/old551/build/bench/rcdem_step_bench
AN4=examples/three_point_bending/study/AN4_NL-B.toml; CK4=results/s42/an4_112000.rcp
C=results/s42/ckpt_tension8/checkpoint_000000012000.h5
[[ -f $C ]] || OMP_NUM_THREADS=1 $B examples/uniaxial/tension.toml 1 12000 1 --save-checkpoint results/s42/ckpt_tension8 > /dev/null
echo "== AN4 NL-B at step 112,000: aebe20d vs 8cfec46"
OMP_NUM_THREADS=1 python3 bench/ab_compare.py 8 $A $B $AN4 100 50 1 --checkpoint $CK4
echo "== AN4 NL-B at step 112,000: 551b674 vs 8cfec46"
OMP_NUM_THREADS=1 python3 bench/ab_compare.py 6 $OLD $B $AN4 100 50 1 --checkpoint $CK4
echo "== cube from C: aebe20d vs 8cfec46"
OMP_NUM_THREADS=1 python3 bench/ab_compare.py 6 $A $B examples/uniaxial/tension.toml 300 20 1 --checkpoint $C
echo "== cracked / intact pairs"
for r in 1 2 3; do
  i=$(OMP_NUM_THREADS=1 $B examples/uniaxial/tension.toml 1000 50 1 | grep -o "steps_per_s=[0-9.]*" | head -1)
  c=$(OMP_NUM_THREADS=1 $B examples/uniaxial/tension.toml 300 20 1 --checkpoint $C | grep -o "steps_per_s=[0-9.]*" | head -1)
  echo "pair $r intact $i cracked $c"
done
echo "== YADE side by side"
THREADS=1 ROUNDS=3 REPEATS=2 CHECKPOINT=$C bash bench/throughput.sh --cracked 200
date -u
