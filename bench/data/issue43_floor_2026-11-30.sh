#!/bin/bash
# Issue 43: cracked / intact and the step's floor (bench/step_floor.py) with this commit's build
# (7d8e06c's step), 1 thread, 5 alternating rounds (log: the .txt beside it). The checkpoint was made
# by e5c324e's step (the same arithmetic):
#   rcdem_step_bench examples/uniaxial/tension.toml 1 12000 1 --save-checkpoint results/s54/ck_cube
cd "$(dirname "$0")/../.."
date -u; nproc; grep -m1 "model name" /proc/cpuinfo; git log -1 --format=%h
/usr/bin/python3 bench/step_floor.py build examples/uniaxial/tension.toml \
  results/s54/ck_cube/checkpoint_000000012000.h5 5
date -u
