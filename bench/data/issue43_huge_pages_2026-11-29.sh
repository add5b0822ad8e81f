#!/bin/bash
# Issue 43: the step in 2 MiB pages (rcdem_step_bench starting again with
# GLIBC_TUNABLES=glibc.malloc.hugetlb=1, as rcdem does: core/huge_pages.hpp), and the step's memory
# floor (bench/step_floor.py), 1 thread, in sequence (log: the .txt beside it). A = e53602d's
# build/bench/rcdem_step_bench (copied aside before the change: 4 KiB pages), B = e5c324e's.
# Checkpoints made by e5c324e's C++ step (the same arithmetic as e53602d's):
#   rcdem_step_bench examples/uniaxial/tension.toml 1 12000 1 --save-checkpoint results/s54/ck_cube
#   rcdem_step_bench examples/three_point_bending/study/AN4_NL-B.toml 1 112000 1 --save-checkpoint results/s54/ck_an4
cd "$(dirname "$0")/../.."
date -u; nproc; grep -m1 "model name" /proc/cpuinfo; cat /sys/kernel/mm/transparent_hugepage/enabled
A=${A:-/tmp/ab/A}; B=build/bench/rcdem_step_bench; CUBE=examples/uniaxial/tension.toml
CKC=${CKC:-results/s54/ck_cube/checkpoint_000000012000.h5}
CKA=${CKA:-results/s54/ck_an4/checkpoint_000000112000.h5}
# As run: the same three comparisons written out in this script; now bench/cracked_ab.sh.
INTACT_ROUNDS=6 bash bench/cracked_ab.sh $A $B $CKC $CKA
echo "== the floor, 4 KiB pages (RCDEM_HUGE_PAGES=off)"
RCDEM_HUGE_PAGES=off /usr/bin/python3 bench/step_floor.py build $CUBE $CKC 5
echo "== the floor, 2 MiB pages"
/usr/bin/python3 bench/step_floor.py build $CUBE $CKC 5
date -u
