#!/usr/bin/python3
"""Where a beam's concrete broke: around its bars or elsewhere, at given midspan deflections.

Usage:
  /usr/bin/python3 tools/broken_near_bars.py RUN_DIR... [--at MM ...] [--radius-over-d K] [--margin MM]

For each run directory (from `rcdem run` or `rcdem study`: scenario.toml, broken_points.csv,
history.csv), counts the concrete local points fully broken (D = 1) by each deflection given with
--at (default 0.6 1.0 1.4 mm), split into those within K x D + margin of a bar's axis (default
1.5 D + 4 mm: the cover and the ring of particles the interface contacts reach) and the rest, with
their facet areas, and the interface points broken by then (history.csv). One line per run and
deflection, key=value pairs; the bars' axes are straight lines from start to end (SPEC 10).

Used in docs/case-study.md ("Session 8: what the plate's peak is made of, and where the beams
break") to compare the interfaces.
"""
import argparse
import csv
import math
import os
import sys
import tomllib


def fail(msg):
    print(f"broken_near_bars: {msg}", file=sys.stderr)
    sys.exit(1)


def bars_of(run_dir):
    path = os.path.join(run_dir, "scenario.toml")
    try:
        with open(path, "rb") as f:
            sc = tomllib.load(f)
    except (OSError, tomllib.TOMLDecodeError) as e:
        fail(f"{path}: cannot read the scenario ({e})")
    bars = []
    for name, b in sc.get("bars", {}).items():
        try:
            bars.append((name, [float(v) for v in b["start"]], [float(v) for v in b["end"]],
                         float(b["diameter"])))
        except (KeyError, TypeError, ValueError):
            fail(f"{path}: bars.{name} needs start, end (3 numbers each) and diameter")
    return bars


def read_rows(path, what, convert):
    """Every row of a CSV file through `convert`; one message and exit 1 if it cannot be read."""
    try:
        with open(path, newline="") as f:
            return [convert(row) for row in csv.DictReader(f)]
    except (OSError, KeyError, ValueError) as e:
        fail(f"{path}: cannot read {what} ({e})")


def distance_to_axis(p, start, end):
    d = [e - s for s, e in zip(start, end)]
    length2 = sum(c * c for c in d)
    t = sum((pc - sc) * dc for pc, sc, dc in zip(p, start, d)) / length2
    t = min(1.0, max(0.0, t))
    q = [sc + t * dc for sc, dc in zip(start, d)]
    return math.dist(p, q)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("runs", nargs="+", metavar="RUN_DIR")
    ap.add_argument("--at", nargs="+", type=float, default=[0.6, 1.0, 1.4], metavar="MM",
                    help="midspan deflections [mm] (default 0.6 1.0 1.4)")
    ap.add_argument("--radius-over-d", type=float, default=1.5, metavar="K")
    ap.add_argument("--margin", type=float, default=4.0, metavar="MM")
    args = ap.parse_args()
    for run in args.runs:
        bars = bars_of(run)
        if not bars:
            fail(f"{run}/scenario.toml: no bars")
        points = read_rows(os.path.join(run, "broken_points.csv"), "the broken points", lambda row: (
            abs(float(row["deflection_m"])) * 1e3,
            any(distance_to_axis((float(row["x_m"]), float(row["y_m"]), float(row["z_m"])), s, e)
                < args.radius_over_d * dia + args.margin * 1e-3 for _, s, e, dia in bars),
            float(row["area_m2"])))
        history = read_rows(os.path.join(run, "history.csv"), "the history", lambda row: (
            abs(float(row["load_displacement_m"])) * 1e3, int(float(row["broken_interface_points"]))))
        for at in args.at:
            near = [a for d, n, a in points if d <= at and n]
            far = [a for d, n, a in points if d <= at and not n]
            iface = max((b for d, b in history if d <= at), default=0)
            print(f"run={run} deflection_mm={at:g} near_bars={len(near)} near_area_m2={sum(near):.4g}"
                  f" elsewhere={len(far)} elsewhere_area_m2={sum(far):.4g}"
                  f" broken_interface_points={iface}")


if __name__ == "__main__":
    main()
