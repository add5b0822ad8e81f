#!/usr/bin/env bash
# rcdem (this commit) and 551b674 (the issue's HEAD) each against YADE's CpmMat in the same rounds,
# intact and cracked, 1 thread: the issue's targets (intact >= 15, cracked >= 6, set on another
# machine where 551b674 read 15.1 and 2.97) read against 551b674 on this one.
# 551b674 built in a worktree: git worktree add -f /tmp/old551 551b674 &&
#   cmake -S /tmp/old551 -B /tmp/old551/build -G Ninja -DCMAKE_BUILD_TYPE=Release -DRCDEM_BUILD_TESTS=OFF &&
#   ninja -C /tmp/old551/build rcdem rcdem_step_bench
# its cracked cube: /tmp/old551/build/rcdem run /tmp/old551/examples/uniaxial/tension.toml \
#   -o results/s56/cube_551run --checkpoint-every 12000   (stopped after step 12,000)
# this commit's: build/bench/rcdem_step_bench examples/uniaxial/tension.toml 1 12000 1 --save-checkpoint results/s54/ck_cube
set -euo pipefail
cd "$(dirname "$0")/../.."
THREADS=1 RCDEM_THREADS=1 ROUNDS=${ROUNDS:-3} REPEATS=2 \
  CHECKPOINT=results/s54/ck_cube/checkpoint_000000012000.h5 \
  REFERENCE_BUILD=/tmp/old551/build REFERENCE_CUBE=/tmp/old551/examples/uniaxial/tension.toml \
  REFERENCE_CHECKPOINT=results/s56/cube_551run/checkpoint_000000012000.rcp \
  bash bench/throughput.sh --cracked 200
