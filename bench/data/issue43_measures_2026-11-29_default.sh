#!/bin/bash
# Issue 43 with softening holds on by default (93c10b9), 1 thread, in sequence (log: the .txt
# beside it). B = this tree's build/bench/rcdem_step_bench. The figure regeneration (nice 19) was
# paused with SIGSTOP for the whole script.
#   1. The cracked cube's checkpoint: examples/uniaxial/tension.toml at step 12,000 (past its peak),
#      made by B.
#   2. Cracked ÷ intact, alternating: B on the cube intact (1000 steps after 50) and from the
#      checkpoint (300 steps after 20), five pairs.
#   3. YADE side by side, intact and cracked (bench/throughput.sh --cracked, from that checkpoint).
cd "$(dirname "$0")/../.."
date -u; nproc; grep -m1 "model name" /proc/cpuinfo
S=results/s47; mkdir -p $S
B=build/bench/rcdem_step_bench; CUBE=examples/uniaxial/tension.toml
CK=$S/ck_cube/checkpoint_000000012000.h5
export OMP_NUM_THREADS=1
[ -f $CK ] || $B $CUBE 1 12000 1 --save-checkpoint $S/ck_cube > $S/ck_cube.log
rate() { "$@" | tr ' ' '\n' | grep '^steps_per_s=' | cut -d= -f2; }
echo "== cracked / intact, alternating (steps/s)"
for r in 1 2 3 4 5; do
  i=$(rate $B $CUBE 1000 50 1); c=$(rate $B $CUBE 300 20 1 --checkpoint $CK)
  echo "pair $r intact $i cracked $c ratio $(/usr/bin/python3 -c "print(round($c / $i, 3))")"
done
echo "== YADE side by side"
THREADS=1 RCDEM_THREADS=1 ROUNDS=3 REPEATS=2 CHECKPOINT=$CK bash bench/throughput.sh --cracked 200 2>&1 |
  grep -v "^$"
date -u
