#!/usr/bin/python3
"""Compares runs with a reference run of the same test (issue 26's quasi-static evidence, SPEC 6):
peak load, deflection at peak, the supports' reactions' peak (SPEC 6's test applies to both) and the
plate's peak over it, the load at fixed deflections (linear interpolation in the
history; the first crossing), steps, time step, wall time and energy balance.

  tools/compare_runs.py REFERENCE_DIR RUN_DIR [RUN_DIR ...] [--at 0.1,0.2,0.5,1,1.5,2] [--markdown]

Deflections in mm on the command line and in the table; SI everywhere else. A deflection a run
did not reach is left blank.
"""
import argparse
import json
import os
import pathlib
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import study_report as sr  # noqa: E402


def load_run(d):
    s = json.loads((pathlib.Path(d) / "summary.json").read_text())
    defl, load = sr.curve(str(d))  # the control's deflection and load, from history.csv
    return s, list(defl), list(load)


def load_at(defl, load, x):
    for i in range(1, len(defl)):
        if defl[i - 1] <= x <= defl[i] and defl[i] > defl[i - 1]:
            t = (x - defl[i - 1]) / (defl[i] - defl[i - 1])
            return load[i - 1] + t * (load[i] - load[i - 1])
    return None


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("reference")
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--at", default="0.1,0.2,0.5,1,1.5,2", help="deflections [mm]")
    ap.add_argument("--markdown", action="store_true")
    a = ap.parse_args()
    at = [float(x) * 1e-3 for x in a.at.split(",")]
    ref, rdefl, rload = load_run(a.reference)
    ref_reactions = sr.reactions(a.reference)
    cols = ["run", "steps", "time step [s]", "wall [s]", "peak [kN]", "δ at peak [mm]",
            "supports' peak [kN]", "peak ÷ supports'"]
    cols += [f"{x * 1e3:g} mm [kN]" for x in at] + ["energy balance"]
    lines = []
    for d in [a.reference] + a.runs:
        s, defl, load = load_run(d)
        cells = [pathlib.Path(d).name, f"{s['steps']:,}", f"{s['time_step_s']:.4g}",
                 f"{s['seconds']:.0f}"]
        def rel(v, r):
            return "" if d == a.reference or r is None or v is None else f" ({100 * (v / r - 1):+.1f}%)"
        cells.append(f"{s['peak_load_N'] / 1e3:.2f}{rel(s['peak_load_N'], ref['peak_load_N'])}")
        cells.append(f"{abs(s['displacement_at_peak_m']) * 1e3:.3f}"
                     f"{rel(abs(s['displacement_at_peak_m']), abs(ref['displacement_at_peak_m']))}")
        rs, ref_rs = sr.reactions(str(d)), ref_reactions
        peak_rs = None if rs is None else float(max(rs))
        cells.append("" if peak_rs is None else
                     f"{peak_rs / 1e3:.2f}{rel(peak_rs, None if ref_rs is None else float(max(ref_rs)))}")
        cells.append("" if peak_rs is None else f"{s['peak_load_N'] / peak_rs:.3f}")
        for x in at:
            v, r = load_at(defl, load, x), load_at(rdefl, rload, x)
            cells.append("" if v is None else f"{v / 1e3:.2f}{rel(v, r)}")
        cells.append(f"{100 * s['energy']['balance_error']:.3f}%")
        lines.append(cells)
    if a.markdown:
        print("| " + " | ".join(cols) + " |")
        print("|" + "---|" * len(cols))
        for c in lines:
            print("| " + " | ".join(c) + " |")
    else:
        w = [max(len(c[i]) for c in lines + [cols]) for i in range(len(cols))]
        for c in [cols] + lines:
            print("  ".join(c[i].rjust(w[i]) for i in range(len(cols))))


if __name__ == "__main__":
    main()
