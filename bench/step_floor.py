#!/usr/bin/python3
"""The step's memory floor on this machine, and how close the step comes to it (issue 43).

A step moves bytes_per_step (rcdem_step_bench's byte model). Most of them stream (arrays walked in
order, which the hardware prefetchers follow); the held contacts' sums and the visited points'
records are read at scattered places (scattered_lines). The floor is the time those bytes take at
this machine's own rates for one thread (rcdem_memory_lines): the streamed bytes at a sequential
read's rate, the scattered lines at independent random lines' rate, in the page size the step runs
in (2 MiB where rcdem asks for huge pages: README, "Huge pages"). No arithmetic, no stores, no
latency a prefetcher cannot hide: a bound no step can beat, not one it should reach.

Runs rcdem_memory_lines once, then the intact state (from step 0) and the cracked one (from a
checkpoint) in alternating rounds at 1 thread, and prints a markdown table: the median rate, the
bytes and scattered lines, the floor's rate, and the rate as a share of it.

Usage:
  bench/step_floor.py BUILD_DIR SCENARIO CHECKPOINT [ROUNDS=3] [INTACT_STEPS=1000]
                      [CRACKED_STEPS=300]
"""
import os
import re
import statistics
import subprocess
import sys


def run(cmd):
    env = dict(os.environ, OMP_NUM_THREADS="1")
    out = subprocess.run(cmd, capture_output=True, text=True, env=env)
    if out.returncode != 0:
        sys.exit(f"step_floor: {' '.join(cmd)} exited with {out.returncode}:\n{out.stderr}")
    return out.stdout


def fields(line):
    return {k: v for k, v in re.findall(r"(\w+)=(\S+)", line)}


def page_size():
    """The pages rcdem_step_bench runs in here, by core/huge_pages.hpp's rule."""
    try:
        mode = open("/sys/kernel/mm/transparent_hugepage/enabled").read()
    except OSError:
        return "4k"
    if "[always]" in mode:
        return "2m"
    if "[madvise]" not in mode:
        return "4k"
    tunables = os.environ.get("GLIBC_TUNABLES", "")
    if "glibc.malloc.hugetlb" in tunables:  # the user's own value is kept
        return "4k" if "glibc.malloc.hugetlb=0" in tunables else "2m"
    return "4k" if "RCDEM_HUGE_PAGES" in os.environ else "2m"


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    build, scenario, checkpoint = sys.argv[1:4]
    rounds = int(sys.argv[4]) if len(sys.argv) > 4 else 3
    intact_steps = sys.argv[5] if len(sys.argv) > 5 else "1000"
    cracked_steps = sys.argv[6] if len(sys.argv) > 6 else "300"
    lines = {}
    for line in run([f"{build}/bench/rcdem_memory_lines"]).splitlines():
        f = fields(line)
        lines[f["page"]] = f
    page = page_size()
    mem = lines[page]
    read_ns, random_ns = float(mem["read_ns_per_line"]), float(mem["random_ns_per_line"])
    bench = f"{build}/bench/rcdem_step_bench"
    states = {
        "intact": [bench, scenario, intact_steps, "50", "1", "--threads", "1"],
        "cracked": [bench, scenario, cracked_steps, "20", "1", "--threads", "1",
                    "--checkpoint", checkpoint],
    }
    seen = {name: [] for name in states}
    for r in range(rounds):
        order = list(states) if r % 2 == 0 else list(reversed(states))
        for name in order:
            seen[name].append(fields(run(states[name]).splitlines()[0]))
    print(f"# rcdem_memory_lines, page={page}: read {read_ns:.2f} ns a line "
          f"({64 / read_ns:.1f} GB/s), random {random_ns:.2f} ns a line, "
          f"latency {float(mem['latency_ns']):.0f} ns")
    print("| state | steps/s (median of %d) | bytes a step | scattered lines | floor: streamed + "
          "scattered | floor steps/s | share of the floor |" % rounds)
    print("|---|---|---|---|---|---|---|")
    rates = {}
    for name, runs in seen.items():
        rate = statistics.median(float(f["steps_per_s"]) for f in runs)
        rates[name] = rate
        last = runs[-1]
        total, scattered = float(last["bytes_per_step"]), float(last["scattered_bytes"])
        count = float(last["scattered_lines"])
        streamed_s = (total - scattered) / 64 * read_ns * 1e-9
        scattered_s = count * random_ns * 1e-9
        floor = 1.0 / (streamed_s + scattered_s)
        print(f"| {name} | {rate:.1f} | {total / 1e6:.1f} MB | {count / 1e3:.0f} k | "
              f"{streamed_s * 1e3:.2f} + {scattered_s * 1e3:.2f} ms | {floor:.0f} | "
              f"{rate / floor:.2f} |")
    print(f"step_floor_cracked_over_intact={rates['cracked'] / rates['intact']:.3f}")


if __name__ == "__main__":
    main()
