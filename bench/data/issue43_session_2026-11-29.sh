#!/bin/bash
# Issue 43: the held contacts' data requested into L2 a block ahead, the spins and frames, then the sums copied
# into lanes first, the list run to whole vectors, the load pass dropped (5dc20f2), against the
# session's start (fe063b5), 1 thread, alternating rounds (log: the .txt beside it); then the
# cracked / intact ratio and the floor (bench/step_floor.py) with 5dc20f2. A = fe063b5's
# build/bench/rcdem_step_bench (copied aside before the change), B = 5dc20f2's. Checkpoints made
# by e5c324e's step (the same arithmetic; the change keeps the bits):
#   rcdem_step_bench examples/uniaxial/tension.toml 1 12000 1 --save-checkpoint results/s54/ck_cube
#   rcdem_step_bench examples/three_point_bending/study/AN4_NL-B.toml 1 112000 1 --save-checkpoint results/s54/ck_an4
cd "$(dirname "$0")/../.."
date -u; nproc; grep -m1 "model name" /proc/cpuinfo; cat /sys/kernel/mm/transparent_hugepage/enabled
A=${A:-/tmp/ab/A}; B=${B:-/tmp/ab/D}; CUBE=examples/uniaxial/tension.toml
CKC=${CKC:-results/s54/ck_cube/checkpoint_000000012000.h5}
CKA=${CKA:-results/s54/ck_an4/checkpoint_000000112000.h5}
INTACT_ROUNDS=6 bash bench/cracked_ab.sh $A $B $CKC $CKA
echo "== the floor and cracked / intact, B"
/usr/bin/python3 bench/step_floor.py build $CUBE $CKC 5
date -u
