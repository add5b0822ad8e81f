#!/usr/bin/python3
"""The partition model of running past one machine (bench/partition_model.cpp, docs/parallel.md)
on the 50 mm cube with a bar (small_run.toml): what its table must satisfy whatever METIS does.

- One part: it owns every body, computes every local point once, has no ghosts, no neighbours,
  no exchange; its projected time is the serial one (speedup 1).
- Every P: the points the ranks compute add up to the specimen's plus the cut contacts' second
  copies (mean x P = total (1 + duplicated share)); the largest rank at least the mean; at most
  P - 1 neighbours; two parts of a connected specimen are each other's only neighbour.
- The time per step is its three terms' sum, the exchange its latency and bytes at the stated
  machine (--latency, --bandwidth), the ghost bytes 88 per ghost body.
- The same table twice (METIS seeded), and the time terms scale with --seconds-per-point.
- Bad arguments: one line, non-zero exit, no table.

usage: check_partition_model.py PARTITION_MODEL SOURCE_DIR
"""
import csv
import math
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checklist import Checklist  # noqa: E402

tool, source = sys.argv[1], sys.argv[2]
scenario = os.path.join(source, "tests", "regression", "small_run.toml")
checks = Checklist()
check = checks.check


def model(out, parts, *extra):
    r = subprocess.run([tool, scenario, out, parts, *extra], capture_output=True, text=True,
                       timeout=300)
    rows = list(csv.DictReader(open(out))) if r.returncode == 0 else []
    return r, rows


with tempfile.TemporaryDirectory() as tmp:
    a = os.path.join(tmp, "a.csv")
    r, rows = model(a, "1,2,3,5", "--latency", "3e-6", "--bandwidth", "5e9")
    check(r.returncode == 0 and [int(x["P"]) for x in rows] == [1, 2, 3, 5],
          f"the model runs for P = 1, 2, 3, 5 ({r.stderr.strip()[-200:]})")
    if rows:
        one = rows[0]
        total = int(one["local_points"])
        check(total > 0 and int(one["max_points"]) == total and int(one["max_ghosts"]) == 0
              and int(one["max_neighbours"]) == 0 and float(one["t_exchange_s"]) == 0
              and float(one["duplicated_share"]) == 0 and float(one["speedup"]) == 1,
              "one part computes every point once, with no ghosts, neighbours or exchange")
        for x in rows[1:]:
            p = int(x["P"])
            mean, dup = float(x["mean_points"]), float(x["duplicated_share"])
            check(math.isclose(mean * p, total * (1 + dup), rel_tol=1e-3) and dup > 0
                  and int(x["max_points"]) >= mean and 0 < int(x["max_neighbours"]) <= p - 1,
                  f"P = {p}: the ranks' points add to the specimen's and the cut contacts' copies "
                  f"({mean:.0f} x {p} against {total} x (1 + {dup}))")
            t = [float(x[k]) for k in ("t_compute_s", "t_exchange_s", "t_allreduce_s")]
            exchange = int(x["max_neighbours"]) * 3e-6 + 88 * int(x["max_ghosts"]) / 5e9
            check(math.isclose(float(x["t_step_s"]), sum(t), rel_tol=1e-3)
                  and math.isclose(t[1], exchange, rel_tol=1e-3)
                  and float(x["max_bytes_per_step"]) == 88 * int(x["max_ghosts"]),
                  f"P = {p}: the step's time is its terms' sum, the exchange latency and bytes")
        check(int(rows[1]["max_neighbours"]) == 1, "two parts: each the other's only neighbour")
    b = os.path.join(tmp, "b.csv")
    r2, rows2 = model(b, "1,2,3,5", "--latency", "3e-6", "--bandwidth", "5e9")
    check(r2.returncode == 0 and open(a).read() == open(b).read(), "the same table twice")
    c = os.path.join(tmp, "c.csv")
    r3, rows3 = model(c, "1,2", "--seconds-per-point", "4e-8")
    check(r3.returncode == 0 and rows and rows3
          and math.isclose(float(rows3[0]["t_compute_s"]),
                           4e-8 * int(rows3[0]["local_points"]), rel_tol=1e-3),
          "the compute time is the stated time per point times the points")
    for args, what in ((["0,2"], "P = 0"), (["2,x"], "P not a number"),
                       (["2", "--latency"], "an option without its value")):
        d = os.path.join(tmp, "d.csv")
        r = subprocess.run([tool, scenario, d, *args], capture_output=True, text=True, timeout=60)
        check(r.returncode != 0 and len(r.stderr.strip().splitlines()) == 1
              and not os.path.exists(d), f"{what}: one line, non-zero exit, no table")

checks.finish()
