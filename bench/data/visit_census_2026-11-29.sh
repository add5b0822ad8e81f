#!/bin/bash
# Issue 43: what the point loop still visits in the cracked cube and the cracked AN4 beam
# (bench/visit_census.cpp), 20 steps from each checkpoint (the cube at step 12,000 made by
# 93c10b9, the AN4 NL-B beam at step 112,000 made by bd1a70a), this tree's build. Log: the .txt
# beside it. Broken points carrying force: C closed and sticking, K the rest (sliding).
cd "$(dirname "$0")/../.."
date -u; nproc; grep -m1 "model name" /proc/cpuinfo; git log -1 --format=%h
export OMP_NUM_THREADS=1
echo "== tension cube"
build/bench/rcdem_visit_census examples/uniaxial/tension.toml 20 \
  ${CKC:-results/s47/ck_cube/checkpoint_000000012000.h5}
echo "== AN4 NL-B"
build/bench/rcdem_visit_census examples/three_point_bending/study/AN4_NL-B.toml 20 \
  ${CKA:-results/s45/ck_an4/checkpoint_000000112000.h5}
