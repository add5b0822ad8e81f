#!/usr/bin/python3
"""A study's cases over several packings (issue 27): per case the mean, standard deviation and
range of a measure; the pre-yield load (tension stiffening); bands of load-deflection curves; and
whether one interface carries more than another, by a paired t-test over the packings.

Used by study_report.py; every function takes plain numbers (SI) and returns plain numbers, so
tests/regression/check_study_statistics.py checks each against values worked by hand.
"""
import math

import numpy as np
from scipy import stats

# The pre-yield load is read at PRE_YIELD_FRACTION of the smallest deflection at which any run of
# the beam first yields a bar (or ends, if none yields), averaged over the last
# PRE_YIELD_WINDOW of that deflection: one deflection per beam, before every run's yield, so the
# load there is the cracked concrete and the bond (tension stiffening), not the steel's yield.
PRE_YIELD_FRACTION = 0.8
PRE_YIELD_WINDOW = 0.1
# A difference is reported as real when the one-sided paired test gives p below this.
SIGNIFICANCE = 0.05


def describe(values):
    """n, mean, sample standard deviation (None for one value), min and max of a list of numbers."""
    v = np.asarray([x for x in values if x is not None], dtype=float)
    if v.size == 0:
        return None
    return {"n": int(v.size), "mean": float(v.mean()),
            "sd": float(v.std(ddof=1)) if v.size > 1 else None,
            "min": float(v.min()), "max": float(v.max())}


def first_yield_deflection(d, yielded_nodes):
    """The deflection of the first history row with a yielded interaction node, or None."""
    hit = np.nonzero(np.asarray(yielded_nodes) > 0)[0]
    return float(d[hit[0]]) if hit.size else None


def pre_yield_deflection(runs):
    """One beam's pre-yield deflection from its runs, each (deflections, first-yield deflection or
    None): PRE_YIELD_FRACTION of the smallest first-yield deflection, a run that never yields
    counting with its last deflection."""
    ends = [fy if fy is not None else float(np.max(d)) for d, fy in runs]
    return PRE_YIELD_FRACTION * min(ends) if ends else None


def load_near(d, p, at, window=PRE_YIELD_WINDOW):
    """The mean load over deflections in [(1 - window) at, at] (cracking ripples make a single
    sample noisy), interpolated at `at` if no row falls inside."""
    d, p = np.asarray(d, dtype=float), np.asarray(p, dtype=float)
    sel = (d >= (1 - window) * at) & (d <= at)
    if np.count_nonzero(sel) >= 2:
        return float(p[sel].mean())
    order = np.argsort(d, kind="stable")
    return float(np.interp(at, d[order], p[order]))


def band(curves, points=200):
    """Curves (deflection, load) of one case over its packings on a common grid up to the
    shortest one's end: (grid, mean, min, max)."""
    end = min(float(np.max(d)) for d, _ in curves)
    grid = np.linspace(0.0, end, points)
    loads = []
    for d, p in curves:
        order = np.argsort(d, kind="stable")
        loads.append(np.interp(grid, np.asarray(d)[order], np.asarray(p)[order]))
    loads = np.array(loads)
    return grid, loads.mean(axis=0), loads.min(axis=0), loads.max(axis=0)


def paired_difference(first, second):
    """Is `first` larger than `second`? Both dicts seed -> value (one beam's two interfaces on
    the same packings). Paired over the common seeds: mean difference, its 95% confidence
    interval (t, two-sided) and the one-sided p-value of first > second (paired t-test), with a
    verdict: 'first > second', 'second > first' (each at p < SIGNIFICANCE one-sided) or
    'not distinguishable'; None where fewer than two seeds are common."""
    seeds = sorted(set(first) & set(second))
    if len(seeds) < 2:
        return None
    a = np.array([first[s] for s in seeds], dtype=float)
    b = np.array([second[s] for s in seeds], dtype=float)
    diff = a - b
    n = len(seeds)
    mean, sd = float(diff.mean()), float(diff.std(ddof=1))
    half = float(stats.t.ppf(0.975, n - 1)) * sd / math.sqrt(n)
    # Equal differences on every packing (sd 0): the sign decides; scipy would return NaN.
    p_greater = (float(stats.ttest_rel(a, b, alternative="greater").pvalue) if sd > 0
                 else 0.0 if mean > 0 else 1.0 if mean < 0 else 0.5)
    # The t distribution is continuous: the opposite one-sided test's p is the complement.
    verdict = ("first > second" if p_greater < SIGNIFICANCE else
               "second > first" if 1.0 - p_greater < SIGNIFICANCE else "not distinguishable")
    return {"seeds": seeds, "n": n, "mean_first": float(a.mean()), "mean_second": float(b.mean()),
            "mean_difference": mean, "ci95": [mean - half, mean + half],
            "p_first_greater": p_greater, "verdict": verdict,
            "test": "paired t-test over packings, one-sided"}
