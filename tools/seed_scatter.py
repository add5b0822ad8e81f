#!/usr/bin/python3
"""The packing's scatter of a beam's peak: one row per run directory given (rcdem run outputs),
with the loading plate's peak, the support reactions' peak, the plateau mean over a deflection
window and the seed; with --smooth W also the peak of the plate's force averaged over W mm of
deflection centred on each history row (the plate force rings: its transients last ~0.01 mm of
deflection at the study's rate). Markdown to stdout. A run still going (or stopped) is read from
its history rows so far, and says so.

Usage: tools/seed_scatter.py [--plateau LO HI (mm, default 1.0 1.4)] [--smooth W (mm)] RUN_DIR...
"""
import json
import sys

import numpy as np
import tomllib
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from study_report import curve, reactions  # noqa: E402  (the study's own readings)


def main(argv):
    lo, hi = 1.0e-3, 1.4e-3
    smooth = None
    while argv[:1] in (["--plateau"], ["--smooth"]):
        try:
            if argv[0] == "--plateau":
                lo, hi = float(argv[1]) * 1e-3, float(argv[2]) * 1e-3
                argv = argv[3:]
            else:
                smooth = float(argv[1]) * 1e-3
                argv = argv[2:]
        except (IndexError, ValueError):
            sys.exit(f"seed_scatter.py: {argv[0]} needs numbers (mm)\n{__doc__}")
    if not argv:
        sys.exit(__doc__)
    extra = f" peak, {smooth * 1e3:g} mm mean |" if smooth else ""
    print(f"| run | seed | peak (plate) | δ at peak | reactions' peak | mean {lo*1e3:g}–{hi*1e3:g} mm | reached |{extra}")
    print("|---|---|---|---|---|---|---|" + ("---|" if smooth else ""))
    for arg in argv:
        run = Path(arg)
        try:
            scenario = tomllib.loads((run / "scenario.toml").read_text())
            defl, plate = curve(str(run))
            sums = reactions(str(run))
        except (OSError, KeyError, ValueError) as e:
            sys.exit(f"seed_scatter.py: {run}: no readable history ({e})")
        if len(defl) == 0:
            sys.exit(f"seed_scatter.py: {run}: the history has no rows yet")
        summary_path = run / "summary.json"
        if summary_path.exists():  # the run's own peak, from every step
            summary = json.loads(summary_path.read_text())
            peak, at = summary["peak_load_N"], abs(summary["displacement_at_peak_m"])
            reached = f"{summary['stop_reason']} at {defl.max() * 1e3:.2f} mm"
        else:  # running or stopped: the history rows' peak so far
            k = int(plate.argmax())
            peak, at = float(plate[k]), float(defl[k])
            reached = f"unfinished, {defl.max() * 1e3:.2f} mm"
        seed = scenario.get("generation", {}).get("seed", "?")
        window = plate[(defl >= lo) & (defl <= hi)]
        mean = f"{window.mean() / 1e3:.2f} kN" if len(window) and defl.max() >= hi else "–"
        row = (f"| {run.name} | {seed} | {peak / 1e3:.2f} kN | {at * 1e3:.3f} mm | "
               f"{'–' if sums is None else f'{sums.max() / 1e3:.2f} kN'} | {mean} | {reached} |")
        if smooth:
            row += f" {smoothed_peak(defl, plate, smooth) / 1e3:.2f} kN |"
        print(row)


def smoothed_peak(defl, force, width):
    """The largest mean of `force` over the rows within width/2 of a row's deflection."""
    order = np.argsort(defl, kind="stable")
    d, f = np.asarray(defl)[order], np.asarray(force)[order]
    csum = np.concatenate(([0.0], np.cumsum(f)))
    lo = np.searchsorted(d, d - 0.5 * width, side="left")
    hi = np.searchsorted(d, d + 0.5 * width, side="right")
    return float(((csum[hi] - csum[lo]) / (hi - lo)).max())


if __name__ == "__main__":
    main(sys.argv[1:])
