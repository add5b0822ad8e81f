#!/bin/bash
# Issue 43: how long the contacts that mix inside and softening points stay so, point by point
# (bench/visit_census.cpp with FOLLOW = 128): from the cube's checkpoint at step 12,000 (made by
# 93c10b9) and the AN4 NL-B beam's at step 112,000 (bd1a70a), 20 steps, then each such contact
# followed 128 steps while it stays visited with every point of its kind (I still I, S still S and
# opening). This tree's build. Log: the .txt beside it.
cd "$(dirname "$0")/../.."
date -u; nproc; grep -m1 "model name" /proc/cpuinfo; git log -1 --format=%h
export OMP_NUM_THREADS=1
echo "== tension cube"
build/bench/rcdem_visit_census examples/uniaxial/tension.toml 20 \
  ${CKC:-results/s47/ck_cube/checkpoint_000000012000.h5} 128 | sed -n '/^mixed/,$p'
echo "== AN4 NL-B"
build/bench/rcdem_visit_census examples/three_point_bending/study/AN4_NL-B.toml 20 \
  ${CKA:-results/s45/ck_an4/checkpoint_000000112000.h5} 128 | sed -n '/^mixed/,$p'
