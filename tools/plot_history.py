#!/usr/bin/python3
"""Load-displacement curve of a run directory (history.csv) as load_displacement.png.

usage: plot_history.py RUN_DIR [RUN_DIR ...] [-o OUT.png] [--labels a,b,c]
One directory: RUN_DIR/load_displacement.png. Several: one figure with a curve each (-o needed).
The displacement is the column summary.json names as displacement_column: the control's (a plate's
'<name>_displacement_m', the mean of several 'control_displacement_m', a pulled bar's
'<name>_pull_displacement_m') or a gauge's ('gauge_<name>_m'); older runs: the control's.
"""
import csv
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def curve(run_dir):
    summary = json.load(open(os.path.join(run_dir, "summary.json")))
    control = summary.get("control", "")
    with open(os.path.join(run_dir, "history.csv")) as f:
        rows = list(csv.DictReader(f))
    column = summary.get("displacement_column", "")
    if column.startswith("gauge_"):
        control = column[len("gauge_"):-len("_m")]
    for key in (column, f"{control}_pull_displacement_m", f"{control}_displacement_m"):
        if rows and key in rows[0]:
            disp = [abs(float(r[key])) for r in rows]
            break
    else:
        sys.exit(f"{run_dir}: history.csv has no displacement column for control '{control}'")
    return disp, [float(r["load_N"]) for r in rows], control


args = sys.argv[1:]
if any(a in ("-h", "--help") for a in args):
    print(__doc__.strip())
    sys.exit(0)
out = None
labels = None
if "-o" in args:
    i = args.index("-o")
    out = args[i + 1]
    del args[i:i + 2]
if "--labels" in args:
    i = args.index("--labels")
    labels = args[i + 1].split(",")
    del args[i:i + 2]
if not args:
    sys.exit(__doc__)
if len(args) > 1 and not out:
    sys.exit("several run directories need -o OUT.png")
fig, ax = plt.subplots(figsize=(7, 4.5))
for k, d in enumerate(args):
    disp, load, control = curve(d)
    if not os.path.isdir(d):
        sys.exit(f"plot_history.py: {d}: not a run directory")
    label = labels[k] if labels and k < len(labels) else os.path.basename(os.path.normpath(d))
    ax.plot([1e3 * x for x in disp], [1e-3 * f for f in load], label=label)
ax.set_xlabel(f"{control} displacement (mm)")
ax.set_ylabel("load (kN)")
ax.grid(True, alpha=0.3)
if len(args) > 1 or labels:
    ax.legend()
fig.tight_layout()
fig.savefig(out or os.path.join(args[0], "load_displacement.png"), dpi=110)
