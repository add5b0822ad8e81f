#!/usr/bin/python3
"""Writes the size series of the tests the paper models (Bosco, Carpinteri and Debernardi: beams
of depth h = 100, 200 and 400 mm, docs/size-series.md) as `rcdem study size_series` runs them:
examples/size_series/study/h<mm>_rho<percent>.toml (the paper's particles) and study/quick/ (the
quick resolution's), one case per depth and steel ratio.

Geometry, from the 100 mm beam of the three-point bending study scaled with h: width 150 mm
(not scaled), span 6h, length 7h, supports and loading plate 0.2h wide, the supports' centres
0.5h from the ends, the bars' axis h/10 above the bottom and their ends 0.1h from the beam's.
The particles are NOT scaled: every size is the same concrete (the calibrated contact set of its
resolution). Steel ratio rho = A_s / (b h), as the paper's (1 bar of 4 mm in 150 x 100 mm is
0.08%); each ratio is realised with 1 to 4 bars of one standard diameter (bar_layout below),
f_y that of Table 3's bar nearest in diameter, the NL-B interface (the case study's best).

usage: make_size_series.py [--out DIR] [--quick-only] [--depths 0.1,0.2,0.4]
                           [--ratios 0,0.08,0.26,0.67,1.05] [--coarsen K] [--velocity V]
Run from the repository root without arguments to rewrite the shipped scenarios.
"""
import argparse
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_tpb_scenarios as tpb  # noqa: E402

B = tpb.B                                 # beam width [m], every size
DEPTHS = (0.100, 0.200, 0.400)            # h [m]
RATIOS = (0.0, 0.08, 0.26, 0.67, 1.05)    # steel ratio A_s / (b h) [%]
STANDARD_DIAMETERS_MM = (4, 5, 6, 8, 10, 12, 14, 16, 20, 25, 28, 32)
MAX_BARS = 4
# Table 3's bars: diameter [mm] -> f_y [Pa] (SPEC 10).
TABLE3_FY = {4: 637e6, 5: 569e6, 8: 441e6, 10: 456e6}

# Loading, as the three-point bending study's at h = 100 mm, scaled with h where a length or a
# period sets it: the deflection to stop at and the ramp (the first bending period grows as
# L^2 / h, i.e. as h for L = 7h). The plate's speed is the same at every size: the deflection
# and the period both grow as h, so the loading spans the same number of periods.
# Speeds and mass scaling: the three-point bending study's (tools/make_tpb_scenarios.py), the full
# resolution at the slowest rate it uses (AN4's).
QUICK = dict(sub="quick", coarsen=2.0, velocity=-0.0125, stop=0.0012, post_peak=None, snapshots=4,
             added_mass=0.01)
FULL = dict(sub="", coarsen=None, velocity=-0.0125, stop=0.002, post_peak=0.001, snapshots=10,
            added_mass=None)
RAMP_AT_100 = 4.0e-3   # s


def bar_layout(ratio_percent, h):
    """(count, diameter [m]) of 1-4 bars of one standard diameter whose A_s / (b h) is nearest
    the ratio (relative error); among layouts within 0.5% of the best, the count nearest 2 (the
    paper's), then the fewer bars. (0, 0) for a plain beam."""
    if ratio_percent == 0:
        return 0, 0.0
    need = ratio_percent / 100 * B * h
    best = None
    for n in range(1, MAX_BARS + 1):
        for d_mm in STANDARD_DIAMETERS_MM:
            area = n * math.pi * (d_mm / 1000) ** 2 / 4
            key = (abs(area / need - 1), n, d_mm)
            if best is None or key[0] < best[0]:
                best = key
    ties = [(abs(n - 2), n, d) for n in range(1, MAX_BARS + 1) for d in STANDARD_DIAMETERS_MM
            if abs(n * math.pi * (d / 1000) ** 2 / 4 / need - 1) <= best[0] + 0.005]
    _, n, d_mm = min(ties)
    return n, d_mm / 1000


def yield_stress(diameter):
    """f_y of Table 3's bar nearest in diameter (the smaller on a tie)."""
    d_mm = diameter * 1000
    nearest = min(TABLE3_FY, key=lambda t: (abs(t - d_mm), t))
    return TABLE3_FY[nearest]


def achieved_ratio(count, diameter, h):
    return count * math.pi * diameter ** 2 / 4 / (B * h)


def case_name(h, ratio):
    return f"h{round(h * 1000)}_rho{ratio:.2f}"


def plate(name, face, x_centre, width, velocity=None, ramp=None):
    return tpb.plate(name, face, x_centre, velocity, ramp, width=width, digits=4)


def bars_text(h, ratio, length):
    count, dia = bar_layout(ratio, h)
    text = ""
    for k in range(count):
        y = B * (2 * k + 1) / (2 * count)
        text += (f"[bars.bar{k + 1}]\nstart = [{0.1 * h:.4f}, {y:.5f}, {h / 10:.4f}]\n"
                 f"end = [{length - 0.1 * h:.4f}, {y:.5f}, {h / 10:.4f}]\n"
                 f"diameter = {dia:g}\nf_y = {yield_stress(dia):.4g}\ninterface = \"NL-B\"\n\n")
    return count, dia, text


def scenario(h, ratio, mode, include):
    length, span = 7 * h, 6 * h
    count, dia, bars = bars_text(h, ratio, length)
    steel = ("plain" if count == 0 else
             f"{count} bar{'s' if count > 1 else ''} of {dia * 1000:g} mm, rho = "
             f"{100 * achieved_ratio(count, dia, h):.3f}% (nominal {ratio:g}%)")
    text = (f"# Size series (docs/size-series.md): h = {h * 1000:g} mm, {steel}"
            f"{' - quick variant' if mode['sub'] else ''}.\n"
            f"# Written by tools/make_size_series.py; SI units.\n"
            f'include = ["{include}"]\n\n'
            f"[specimen]\nshape = \"beam\"\nsize = [{length:g}, {B}, {h:g}]   # length x, width y, depth z [m]\n\n"
            f"[generation]\nseed = 1\n\n")
    text += tpb.coarse_particles(mode["coarsen"]) + bars
    x0 = (length - span) / 2
    text += (plate("support_left", "z-", x0, 0.2 * h) + "\n"
             + plate("support_right", "z-", length - x0, 0.2 * h) + "\n"
             + plate("load", "z+", length / 2, 0.2 * h, velocity=mode["velocity"],
                     ramp=RAMP_AT_100 * h / 0.1))
    scale = h / 0.1
    post_peak = mode["post_peak"] and mode["post_peak"] * scale
    text += tpb.loading_tail(mode, count > 0, mode["stop"] * scale, post_peak,
                             "or this far past the peak's deflection")
    return text


def parse_args():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default=os.path.join("examples", "size_series", "study"),
                    help="directory of the full-resolution scenarios (quick ones in OUT/quick)")
    ap.add_argument("--quick-only", action="store_true", help="write only OUT/quick")
    ap.add_argument("--depths", default=",".join(f"{h:g}" for h in DEPTHS), help="h [m], comma-separated")
    ap.add_argument("--ratios", default=",".join(f"{r:g}" for r in RATIOS), help="rho [%%], comma-separated")
    ap.add_argument("--coarsen", type=float, default=QUICK["coarsen"],
                    help="the quick particles' diameters over the paper's")
    ap.add_argument("--velocity", type=float, help="the loading plate's speed [m/s] (both resolutions)")
    return ap.parse_args()


def main():
    a = parse_args()
    depths = [float(v) for v in a.depths.split(",")]
    ratios = [float(v) for v in a.ratios.split(",")]
    quick = dict(QUICK, coarsen=a.coarsen)
    modes = [quick] if a.quick_only else [FULL, quick]
    root = os.path.abspath(os.path.dirname(os.path.abspath(__file__)) + "/..")
    for mode in modes:
        if a.velocity is not None:
            mode = dict(mode, velocity=-abs(a.velocity))
        out = os.path.join(a.out, mode["sub"])
        os.makedirs(out, exist_ok=True)
        contact = "calibrated_contact_quick.toml" if mode["sub"] else "calibrated_contact.toml"
        include = os.path.relpath(os.path.join(root, "examples", contact), os.path.abspath(out))
        for h in depths:
            for ratio in ratios:
                path = os.path.join(out, case_name(h, ratio) + ".toml")
                with open(path, "w") as f:
                    f.write(scenario(h, ratio, mode, include))
                print(path)


if __name__ == "__main__":
    main()
