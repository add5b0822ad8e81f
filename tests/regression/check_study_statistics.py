#!/usr/bin/python3
"""The study report's statistics over packings (tools/study_ensemble.py, issue 27) against values
worked by hand: mean, sample sd and range; the first yield and the pre-yield deflection and load;
bands on a common grid; the paired t-test against the closed form of Student's t with 2 degrees
of freedom, F(t) = 1/2 + t / (2 sqrt(2 + t^2)), in both directions; the transition at a beam on
each packing (tools/study_report.py) on hand-made classes.

usage: check_study_statistics.py SOURCE_DIR
"""
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(sys.argv[1], "tools"))
from checklist import Checklist  # noqa: E402
import study_ensemble as ens  # noqa: E402

checks = Checklist()
check = checks.check


def close(a, b, tol=1e-12):
    return abs(a - b) <= tol * max(1.0, abs(b))


e = ens.describe([1.0, 2.0, 3.0, 4.0, None])
check(e["n"] == 4 and close(e["mean"], 2.5) and close(e["sd"], math.sqrt(5 / 3))
      and e["min"] == 1.0 and e["max"] == 4.0, f"describe: n, mean, sample sd, range ({e})")
one = ens.describe([7.0])
check(one["n"] == 1 and one["sd"] is None and one["mean"] == 7.0, "describe: one value has no sd")
check(ens.describe([None]) is None, "describe: nothing to describe")

d = np.array([0.0, 1e-3, 2e-3, 3e-3])
check(ens.first_yield_deflection(d, [0, 0, 1, 2]) == 2e-3, "first yield: the first row with one")
check(ens.first_yield_deflection(d, [0, 0, 0, 0]) is None, "first yield: none")
pre = ens.pre_yield_deflection([(np.array([0.0, 2e-3]), 1.5e-3), (np.array([0.0, 1.2e-3]), None)])
check(close(pre, 0.8 * 1.2e-3), f"pre-yield deflection: 0.8 x the smallest of 1.5 and the unyielded "
      f"run's end 1.2 mm ({pre * 1e3:.4f} mm)")

dd = np.linspace(0.0, 1.0, 11)
check(close(ens.load_near(dd, 10 * dd, 1.0), 9.5), "load near 1.0: mean of the rows at 0.9 and 1.0")
check(close(ens.load_near(dd, 10 * dd, 0.55), 5.5), "load near 0.55: interpolated (one row inside)")

g, mean, lo, hi = ens.band([(np.array([0.0, 1.0, 2.0]), np.array([0.0, 1.0, 2.0])),
                            (np.array([0.0, 1.0]), np.array([0.0, 3.0]))], points=3)
check(np.allclose(g, [0, 0.5, 1]) and np.allclose(mean, [0, 1, 2]) and np.allclose(lo, [0, 0.5, 1])
      and np.allclose(hi, [0, 1.5, 3]), "band: common grid to the shorter curve's end, mean, min, max")


def p_greater_df2(diffs):
    """One-sided p of mean > 0 for three paired differences, from the closed form."""
    n = len(diffs)
    m = sum(diffs) / n
    sd = math.sqrt(sum((x - m) ** 2 for x in diffs) / (n - 1))
    t = m / (sd / math.sqrt(n))
    return 0.5 - t / (2 * math.sqrt(2 + t * t)), m, sd


first = {1: 10.0, 2: 12.0, 3: 11.0}
second = {1: 9.0, 2: 10.0, 3: 10.5, 4: 99.0}  # seed 4 has no partner: left out
t = ens.paired_difference(first, second)
p, m, sd = p_greater_df2([1.0, 2.0, 0.5])
half = 4.302652729911275 * sd / math.sqrt(3)  # t(0.975, 2)
check(t["seeds"] == [1, 2, 3] and close(t["mean_difference"], m) and close(t["p_first_greater"], p, 1e-9)
      and close(t["ci95"][0], m - half, 1e-9) and close(t["ci95"][1], m + half, 1e-9),
      f"paired test on the common seeds: difference {m:.4f}, p {p:.5f} (closed form), CI ± {half:.4f}")
check(t["verdict"] == "not distinguishable", f"p = {p:.3f} > 0.05: not distinguishable")
strong = {1: 8.0, 2: 10.0, 3: 9.2}
t = ens.paired_difference(first, strong)
p, _, _ = p_greater_df2([2.0, 2.0, 1.8])
check(close(t["p_first_greater"], p, 1e-9) and t["verdict"] == "first > second",
      f"a consistent difference: p {p:.2e}, first > second")
t = ens.paired_difference(strong, first)
check(close(t["p_first_greater"], 1 - p, 1e-9) and t["verdict"] == "second > first",
      "the same pair reversed: second > first")
check(ens.paired_difference({1: 1.0}, {1: 2.0, 2: 3.0}) is None, "one common seed: no test")

import study_report  # noqa: E402  (after the statistics: it loads matplotlib)


def run(model, interface, seed, ductile):
    return {"model": model, "interface": interface, "seed": seed,
            "class": "ductile" if ductile else "brittle"}


runs = [run("AN0", "none", 1, False), run("AN1", "NL-B", 1, False), run("AN2", "NL-B", 1, True),
        run("AN2", "EL", 1, False), run("AN3", "NL-B", 1, True), run("AN4", "NL-B", 1, True),
        run("AN0", "none", 2, False), run("AN2", "NL-B", 2, True), run("AN4", "NL-B", 2, False),
        run("AN1", "NL-B", 3, True), run("AN0", "none", 3, False), run("AN2", "NL-B", 4, False)]
rep = {"cases": {f"r{i}": v for i, v in enumerate(runs)}}
lines = "\n".join(study_report.transition_by_packing(rep))
check(rep["transition_by_seed"] == {"1": "AN2", "2": None, "3": "AN1", "4": None},
      f"transition per packing: at AN2 (an EL run's class ignored), not established without AN1, "
      f"at AN1, none ({rep['transition_by_seed']})")
check("packing 2: AN0 brittle, AN2 ductile, AN4 brittle → transition not established (AN1 not run); "
      "brittle above it: AN4." in lines and "packing 4: AN2 brittle → transition not seen." in lines,
      "the per-packing lines name the missing beam and a brittle beam above the first ductile one")
checks.finish()
