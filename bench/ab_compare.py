#!/usr/bin/python3
"""A/B comparison of two builds' step rate, in alternating rounds (bench/RESULTS.md, session 13).

This machine's speed drifts 2-3x over minutes (RESULTS.md, sessions 11-12), so two binaries timed
minutes apart say nothing. Each round runs both, back to back, in an order that alternates from
round to round (A B, B A, ...), so that a drift within a round favours neither. Per round the
ratio B/A; over the rounds the medians, the best figures, the median ratio and a sign test: how
many rounds B won, and the two-sided probability of at least that lopsided a split if A and B
were equally fast. A change is worth keeping when the sign test says so, not when one pair does.

Usage:
  bench/ab_compare.py ROUNDS BIN_A BIN_B [ARG...]
    BIN_A, BIN_B: two rcdem_step_bench binaries (e.g. a worktree's build of the parent and this
    tree's), each run as `BIN ARG...` with the environment as given (set OMP_NUM_THREADS). Each
    may carry arguments of its own, split as a shell splits words (no shell runs): one binary with
    and without a setting, "build/bench/rcdem_step_bench --set KEY=false" against
    build/bench/rcdem_step_bench, compares code in the same place (where the code lands moves the
    step by a few percent on some machines, bench/RESULTS.md).
  Example:
    git worktree add -f /tmp/old HEAD && cmake -S /tmp/old -B /tmp/old/build -G Ninja \\
      -DCMAKE_BUILD_TYPE=Release -DRCDEM_BUILD_TESTS=OFF && ninja -C /tmp/old/build rcdem_step_bench
    OMP_NUM_THREADS=2 bench/ab_compare.py 6 /tmp/old/build/bench/rcdem_step_bench \\
      build/bench/rcdem_step_bench examples/three_point_bending/study/AN4_NL-B.toml 100 10 2 \\
      --checkpoint results/bench_ckpt/checkpoint_000000064000.h5
Prints one line per round, then a summary; the last line is `ab_median_ratio=<B/A>`.
"""
import math
import re
import shlex
import statistics
import subprocess
import sys


def steps_per_s(command, args):
    words = shlex.split(command)
    if not words:
        sys.exit("ab_compare: BIN_A and BIN_B must name a binary")
    binary, *own = words
    try:
        out = subprocess.run([binary, *args, *own], capture_output=True, text=True)
    except OSError as e:
        sys.exit(f"ab_compare: cannot run {binary}: {e.strerror}")
    if out.returncode != 0:
        sys.exit(f"ab_compare: {binary} exited with {out.returncode}:\n{out.stderr.strip()}")
    m = re.search(r"\bsteps_per_s=([0-9.eE+-]+)", out.stdout)
    if not m:
        sys.exit(f"ab_compare: no 'steps_per_s=' in the output of {binary}")
    return float(m.group(1))


def sign_test(wins, n):
    """Two-sided p of a split at least as lopsided as wins of n under a fair coin."""
    k = max(wins, n - wins)
    tail = sum(math.comb(n, i) for i in range(k, n + 1)) / 2.0**n
    return min(1.0, 2.0 * tail)


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__.split("\n\n")[2])
    try:
        rounds = int(sys.argv[1])
    except ValueError:
        rounds = 0
    if rounds < 1:
        sys.exit("ab_compare: ROUNDS must be a whole number >= 1")
    a, b, args = sys.argv[2], sys.argv[3], sys.argv[4:]
    ra, rb, ratios = [], [], []
    for k in range(rounds):
        if k % 2 == 0:
            x = steps_per_s(a, args)
            y = steps_per_s(b, args)
        else:
            y = steps_per_s(b, args)
            x = steps_per_s(a, args)
        ra.append(x)
        rb.append(y)
        ratios.append(y / x)
        print(f"round {k + 1} ({'AB' if k % 2 == 0 else 'BA'}): A {x:.2f}  B {y:.2f}  B/A {y / x:.3f}",
              flush=True)
    wins = sum(1 for r in ratios if r > 1.0)
    print(f"# A: median {statistics.median(ra):.2f}, best {max(ra):.2f} steps/s ({a})")
    print(f"# B: median {statistics.median(rb):.2f}, best {max(rb):.2f} steps/s ({b})")
    print(f"# B faster in {wins} of {rounds} rounds; sign test p = {sign_test(wins, rounds):.3f} "
          f"(two-sided; below 0.05 needs 6 of 6, 7 of 7, 8 of 8, 8 of 9 or 9 of 10)")
    print(f"ab_median_ratio={statistics.median(ratios):.4f}")


if __name__ == "__main__":
    main()
