#!/bin/bash
# Issue 43: holding contacts whose unbroken points are partly softening and partly inside their
# envelope (branch tried/mixed-holds, fc2d99f: solver.hold_mixed_contacts on) against aa265d2,
# 1 thread, alternating rounds (log: the .txt beside it). A = aa265d2's rcdem_step_bench, B =
# fc2d99f's (Release, portable builds of each). Then the visit census of each build, 20 steps from
# the cube's checkpoint. The figure regeneration (nice 19) was paused with SIGSTOP throughout.
cd "$(dirname "$0")/../.."
date -u; nproc; grep -m1 "model name" /proc/cpuinfo
A=${A:-/tmp/base49/build/bench/rcdem_step_bench}; B=${B:-/tmp/sb_mixed}
CUBE=examples/uniaxial/tension.toml; AN4=examples/three_point_bending/study/AN4_NL-B.toml
CKC=${CKC:-results/s47/ck_cube/checkpoint_000000012000.h5}
CKA=${CKA:-results/s45/ck_an4/checkpoint_000000112000.h5}
export OMP_NUM_THREADS=1
ab() { /usr/bin/python3 bench/ab_compare.py "$@" 2>&1 | grep -v "^round"; }
echo "== cube at step 12,000, 300 steps after 20: A vs B"
ab 8 $A $B $CUBE 300 20 1 --checkpoint $CKC
echo "== AN4 NL-B at step 112,000, 100 steps after 50: A vs B"
ab 6 $A $B $AN4 100 50 1 --checkpoint $CKA
echo "== visit census, A's build (aa265d2) then B's (fc2d99f)"
${CENSUS_A:-/tmp/base49/build/bench/rcdem_visit_census} $CUBE 20 $CKC | head -1
${CENSUS_B:-/tmp/census_mixed} $CUBE 20 $CKC | head -1
date -u
