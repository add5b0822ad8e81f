#!/usr/bin/python3
"""Copies what docs/ keeps of a study directory (issue 27): the tables (table3.md with the commit
that ran it, report.json, peak_loads.csv, cases.csv), Figure 10 (a-f), the crack heights, and
Figures 8 and 9 of the first packing's NL-B runs and AN0, and cases.md: per run its steps, wall
time and energy-balance error as a table for bench/RESULTS.md. Everything else (histories,
snapshots, every run's figures) stays in the study directory.

usage: publish_study.py STUDY_DIR DEST_DIR   (run tools/study_report.py STUDY_DIR first)
"""
import csv
import glob
import json
import os
import shutil
import sys


def runs_table(study, runs):
    """cases.md: each finished run's cost and energy balance, with the commit that ran them."""
    commit = json.load(open(os.path.join(study, "report.json"))).get("commit", "commit not recorded")
    lines = [f"Runs of the study ({commit}; wall time of each run on its own core):", "",
             "| case | seed | steps | wall time [min] | steps/s | energy balance error | stop |",
             "|---|---|---|---|---|---|---|"]
    steps = wall = 0.0
    for r in runs:
        n, t = int(r["steps"]), float(r["wall_time_s"])
        steps, wall = steps + n, wall + t
        lines.append(f"| {r['case']} | {r.get('seed') or '-'} | {n:,} | {t / 60:.1f} | "
                     f"{n / t if t else 0:.0f} | {100 * float(r['energy_balance_error']):.2g}% | "
                     f"{r['stop_reason']} |")
    lines.append(f"| all {len(runs)} runs (sums) | | {int(steps):,} | {wall / 60:.1f} | "
                 f"{steps / wall if wall else 0:.0f} | | |")
    return "\n".join(lines) + "\n"


def main(study, dest):
    if not os.path.exists(os.path.join(study, "table3.md")):
        sys.exit(f"{study}: no table3.md (run tools/study_report.py {study} first)")
    os.makedirs(dest, exist_ok=True)
    files = ["table3.md", "report.json", "peak_loads.csv", "cases.csv", "crack_height.png"]
    files += [os.path.basename(f) for f in sorted(glob.glob(os.path.join(study, "figure10*.png")))]
    finished = [r for r in csv.DictReader(open(os.path.join(study, "cases.csv")))
                if r["status"] == "finished"]
    with open(os.path.join(dest, "cases.md"), "w") as f:
        f.write(runs_table(study, finished))
    print(os.path.join(dest, "cases.md"))
    runs = [r for r in finished if r["interface"] in ("NL-B", "none")]
    first = {}
    for r in runs:
        seed = int(r["seed"]) if r.get("seed") else 0
        if r["case"] not in first or seed < first[r["case"]][0]:
            first[r["case"]] = (seed, r.get("directory") or r["case"])
    for _, directory in sorted(first.values(), key=lambda x: x[1]):
        files += [f"figure9_{directory}.png", f"figure8_{directory}.png"]
    for f in files:
        src = os.path.join(study, f)
        if os.path.exists(src):
            shutil.copyfile(src, os.path.join(dest, f))
            print(os.path.join(dest, f))


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
