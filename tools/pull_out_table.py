#!/usr/bin/python3
"""The pull-out table of docs/reinforcement.md, and the numbers its text quotes, from the run
directories of `rcdem run examples/pull_out/{EL,NL-A,NL-B}.toml` (history.csv, summary.json), so
that they are regenerated rather than edited by hand.

usage: pull_out_table.py DIR_EL DIR_NL-A DIR_NL-B
"""
import csv
import json
import os
import sys

LABELS = ("EL", "NL-A", "NL-B")


def rows(d):
    with open(os.path.join(d, "history.csv")) as f:
        return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]


def summary(d):
    with open(os.path.join(d, "summary.json")) as f:
        return json.load(f)


def first(hist, key, above):
    """The first row whose `key` exceeds `above`, or None."""
    return next((r for r in hist if r[key] > above), None)


def describe(label, d):
    hist, s = rows(d), summary(d)
    slip = "bar_pull_displacement_m"
    peak = max(hist, key=lambda r: r["load_N"])
    last = hist[-1]
    balance = f"{100 * s['energy']['balance_error']:.3f}%"
    broken = int(last["broken_interface_points"])
    if s["stop_reason"] == "displacement" and peak is last:
        head = f"no peak: {peak['load_N'] / 1e3:.1f} kN at {1e3 * peak[slip]:.2f} mm (the stop)"
        row = f"| {label} | {head} | – | {broken} | {balance} |"
    else:
        row = (f"| {label} | {peak['load_N'] / 1e3:.1f} kN | {1e3 * peak[slip]:.3f} mm | {broken} | "
               f"{balance} |")
    notes = [f"{label}: stop {s['stop_reason']} at {1e3 * last[slip]:.3f} mm "
             f"({100 * last['load_N'] / peak['load_N']:.0f}% of the peak), {s['steps']} steps, "
             f"{s['seconds']:.1f} s"]
    crack = s.get("first_cracking")
    if crack:
        notes.append(f"{label}: first broken concrete point at {crack['load_N'] / 1e3:.1f} kN")
    at01 = first(hist, slip, 1e-4)
    if at01:
        notes.append(f"{label}: broken points {int(at01['broken_points'])} at 0.1 mm, "
                     f"{int(last['broken_points'])} at the end")
    yielded = first(hist, "yielded_nodes", 0.5)
    if yielded:
        notes.append(f"{label}: first yielded node at {yielded['load_N'] / 1e3:.1f} kN "
                     f"({1e3 * yielded[slip]:.3f} mm)")
    return row, notes


def main(argv):
    if len(argv) != 3:
        sys.exit(__doc__)
    print("| interface | peak pull-out force | slip at peak | broken interface points at the end | "
          "energy balance error |")
    print("|---|---|---|---|---|")
    notes = []
    versions = set()
    for label, d in zip(LABELS, argv):
        row, n = describe(label, d)
        print(row)
        notes += n
        versions.add(summary(d)["rcdem"]["git_hash"])
    print()
    for n in notes:
        print("- " + n)
    print(f"- rcdem {', '.join(sorted(versions))}")


if __name__ == "__main__":
    main(sys.argv[1:])
