#!/bin/bash
# Issue 43's measures on 6c14817's binaries (1 thread), in sequence (log: the .txt beside it).
# /tmp/old551: `git worktree add -f /tmp/old551 551b674`, built with
#   cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DRCDEM_BUILD_TESTS=OFF && ninja -C build rcdem rcdem_step_bench
# results/s42/an4_112000.rcp: 551b674's `rcdem run examples/three_point_bending/study/AN4_NL-B.toml
#   --checkpoint-every 64000`, resumed with `--resume DIR --checkpoint-every 16000` (the checkpoint at
#   step 112,000: 1.15 mm of deflection, 35.3 kN, the load still rising as the bars carry it).
# results/s42/ckpt_tension: `rcdem_step_bench examples/uniaxial/tension.toml 1 12000 1
#   --save-checkpoint results/s42/ckpt_tension` (6c14817, 1 thread).
cd /work/main
date -u; nproc; grep -m1 "model name" /proc/cpuinfo
C=results/s42/ckpt_tension/checkpoint_000000012000.h5
echo "== AN4 NL-B at step 112,000 (551b674's checkpoint), 551b674 vs 6c14817"
OMP_NUM_THREADS=1 python3 bench/ab_compare.py 6 /tmp/old551/build/bench/rcdem_step_bench build/bench/rcdem_step_bench examples/three_point_bending/study/AN4_NL-B.toml 100 50 1 --checkpoint results/s42/an4_112000.rcp
echo "== cracked / intact pairs"
for r in 1 2 3; do
  i=$(OMP_NUM_THREADS=1 build/bench/rcdem_step_bench examples/uniaxial/tension.toml 1000 50 1 | grep -o "steps_per_s=[0-9.]*" | head -1)
  c=$(OMP_NUM_THREADS=1 build/bench/rcdem_step_bench examples/uniaxial/tension.toml 300 20 1 --checkpoint $C | grep -o "steps_per_s=[0-9.]*" | head -1)
  echo "pair $r intact $i cracked $c"
done
echo "== YADE side by side"
THREADS=1 ROUNDS=3 REPEATS=2 CHECKPOINT=$C bash bench/throughput.sh --cracked 200
date -u
