#!/bin/bash
# Issue 43: the held contacts' kernel loading every line of its listed sums before the gather,
# in place of software prefetches (the block listing's and 4 ahead in the gather), 1 thread, in
# sequence (log: the .txt beside it). A = 53cf237's build (a worktree's rcdem_step_bench,
# Release, portable), B = ceb49d4's build/bench/rcdem_step_bench.
# Checkpoints: the tension cube at step 12,000 made by 93c10b9 (bench/data/
# issue43_measures_2026-11-29_default.sh, same arithmetic); the AN4 NL-B beam at step 112,000
# made by bd1a70a (format 8: every clock restarts at 0, the warm-up holds again). The figure
# regeneration (nice 19) was paused with SIGSTOP for the whole script.
cd "$(dirname "$0")/../.."
date -u; nproc; grep -m1 "model name" /proc/cpuinfo
A=${A:-/tmp/base53/build/bench/rcdem_step_bench}; B=build/bench/rcdem_step_bench
CUBE=examples/uniaxial/tension.toml; AN4=examples/three_point_bending/study/AN4_NL-B.toml
CKC=${CKC:-results/s47/ck_cube/checkpoint_000000012000.h5}
CKA=${CKA:-results/s45/ck_an4/checkpoint_000000112000.h5}
export OMP_NUM_THREADS=1
ab() { /usr/bin/python3 bench/ab_compare.py "$@" 2>&1 | grep -v "^round"; }
echo "== cube at step 12,000, 300 steps after 20: A vs B"
ab 10 $A $B $CUBE 300 20 1 --checkpoint $CKC
echo "== AN4 NL-B at step 112,000, 100 steps after 50: A vs B"
ab 6 $A $B $AN4 100 50 1 --checkpoint $CKA
rate() { "$@" | tr ' ' '\n' | grep '^steps_per_s=' | cut -d= -f2; }
echo "== B: cracked / intact, alternating (steps/s)"
for r in 1 2 3 4 5; do
  i=$(rate $B $CUBE 1000 50 1); c=$(rate $B $CUBE 300 20 1 --checkpoint $CKC)
  echo "pair $r intact $i cracked $c ratio $(/usr/bin/python3 -c "print(round($c / $i, 3))")"
done
date -u
