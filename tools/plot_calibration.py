#!/usr/bin/python3
"""Figure 7 of the paper from a calibration directory: stress-strain and damage-strain curves of
the uniaxial compression and tension tests (curve_compression.csv, curve_tension.csv).

usage: plot_calibration.py CALIBRATION_DIR   -> CALIBRATION_DIR/figure7.png
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {k: [float(r[k]) for r in rows] for k in rows[0]}


d = sys.argv[1]
fig, axes = plt.subplots(2, 2, figsize=(11, 8))
for col, mode in enumerate(("compression", "tension")):
    path = os.path.join(d, f"curve_{mode}.csv")
    if not os.path.exists(path):
        continue
    c = read(path)
    strain_permille = [1e3 * e for e in c["strain"]]
    ax = axes[0][col]
    ax.plot(strain_permille, [s / 1e6 for s in c["stress_Pa"]], "k-", label="face gauges")
    if "interior_strain" in c:
        # E and nu come from this gauge (docs/model.md 7); up to the peak only, since a crack
        # outside the central region unloads it.
        peak = max(range(len(c["stress_Pa"])), key=lambda i: c["stress_Pa"][i])
        ax.plot([1e3 * e for e in c["interior_strain"][:peak + 1]],
                [s / 1e6 for s in c["stress_Pa"][:peak + 1]], "C1--", label="interior gauge")
        ax.legend()
    ax.set_xlabel("axial strain (‰)")
    ax.set_ylabel("axial stress (MPa)")
    ax.set_title(f"uniaxial {mode}: peak {max(c['stress_Pa']) / 1e6:.2f} MPa")
    ax.grid(True, alpha=0.3)
    ax = axes[1][col]
    ax.plot(strain_permille, [100 * x for x in c["damaged_fraction"]], label="damaged (0 < D < 1)")
    ax.plot(strain_permille, [100 * x for x in c["broken_fraction"]], label="broken (D = 1)")
    ax.set_xlabel("axial strain (‰)")
    ax.set_ylabel("local contact points (%)")
    ax.legend()
    ax.grid(True, alpha=0.3)
fig.tight_layout()
fig.savefig(os.path.join(d, "figure7.png"), dpi=110)
