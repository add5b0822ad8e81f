#!/usr/bin/python3
"""The size series (docs/size-series.md): the shipped scenarios are the generator's and follow the
series' rules; the type-1 fit recovers a known law; a tiny series runs end to end through
`rcdem study size_series` and its report.

usage: check_size_series.py RCDEM_BINARY SOURCE_DIR
"""
import json
import math
import os
import subprocess
import sys
import tempfile
import tomllib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checklist import Checklist  # noqa: E402

rcdem, source = sys.argv[1], sys.argv[2]
sys.path.insert(0, os.path.join(source, "tools"))
import make_size_series as mss  # noqa: E402
import size_series_report as ssr  # noqa: E402

checks = Checklist()
check = checks.check
GENERATOR = os.path.join(source, "tools", "make_size_series.py")
SHIPPED = os.path.join(source, "examples", "size_series", "study")


def without_include(path):
    with open(path) as f:
        return [line for line in f if not line.startswith("include = ")]


def centre(plate):
    return (plate["extent"][0] + plate["extent"][1]) / 2


def check_rules(path, quick):
    """One scenario against the series' rules; returns its achieved ratio [%] and nominal one."""
    name = os.path.basename(path)[:-5]
    h_mm, nominal = name[1:].split("_rho")
    h, nominal = float(h_mm) / 1000, float(nominal)
    with open(path, "rb") as f:
        s = tomllib.load(f)
    length, b, depth = s["specimen"]["size"]
    p = s["plates"]
    ok = (abs(depth - h) < 1e-12 and b == 0.15 and abs(length - 7 * h) < 1e-12
          and abs(centre(p["support_right"]) - centre(p["support_left"]) - 6 * h) < 1e-9
          and abs(centre(p["load"]) - length / 2) < 1e-9
          and all(abs(q["extent"][1] - q["extent"][0] - 0.2 * h) < 1e-9 for q in p.values()))
    bars = list(s.get("bars", {}).values())
    area = sum(math.pi * x["diameter"] ** 2 / 4 for x in bars)
    ok = ok and all(abs(x["start"][2] - h / 10) < 1e-12 and x["interface"] == "NL-B" for x in bars)
    # f_y: Table 3's bar nearest in diameter.
    ok = ok and all(x["f_y"] == mss.yield_stress(x["diameter"]) for x in bars)
    g = s.get("generation", {})
    coarse = g.get("aggregate", {}).get("d_max") == 0.024 and g.get("mortar", {}).get("d_max") == 0.018
    ok = ok and (coarse if quick else "aggregate" not in g)
    return ok, 100 * area / (b * h), nominal


with tempfile.TemporaryDirectory() as tmp:
    # 1. The shipped scenarios are the generator's, byte for byte.
    regen = os.path.join(tmp, "regen")
    r = subprocess.run([sys.executable, GENERATOR, "--out", regen], capture_output=True, text=True,
                       cwd=source)
    names = sorted(f for f in os.listdir(SHIPPED) if f.endswith(".toml"))
    same = r.returncode == 0 and len(names) == 15 and all(
        without_include(os.path.join(SHIPPED, sub, n)) == without_include(os.path.join(regen, sub, n))
        for sub in ("", "quick") for n in names)
    check(same, "examples/size_series/study (15 cases, and quick/) is tools/make_size_series.py's "
          "output, byte for byte but the include's path (relative to the directory written)")

    # 2. Every case follows the series' rules; every ratio is met within 5% by standard bars.
    worst = 0.0
    rules = True
    for sub, quick in (("", False), ("quick", True)):
        for n in names:
            ok, achieved, nominal = check_rules(os.path.join(SHIPPED, sub, n), quick)
            rules = rules and ok
            if nominal > 0:
                worst = max(worst, abs(achieved / nominal - 1))
            else:
                rules = rules and achieved == 0
    check(rules, "span 6h, length 7h, plates 0.2h wide, bars at h/10 with NL-B and Table 3's f_y "
          "of the nearest bar; quick particles twice the paper's")
    check(worst < 0.05, f"every steel ratio met within 5% (worst {100 * worst:.1f}%)")
    check(mss.bar_layout(0.08, 0.1) == (1, 0.004) and mss.bar_layout(1.05, 0.1) == (2, 0.010),
          "at h = 100 mm the ratios are the paper's bars (AN1 1Φ4 ... AN4 2Φ10)")

    # 3. The fit recovers a type-1 law from points on it.
    hs = [0.05, 0.1, 0.2, 0.4, 0.8]
    law = dict(f_r_inf_Pa=3.6e6, D_b_m=0.045, r=1.3)
    sig = [ssr.sel(h, law["f_r_inf_Pa"], law["D_b_m"], law["r"]) for h in hs]
    fit = ssr.fit_size_effect(hs, sig)
    check(fit is not None and all(abs(fit[k] / law[k] - 1) < 1e-5 for k in law),
          f"the type-1 fit recovers f_r_inf, D_b, r from exact points ({fit and {k: fit[k] for k in law}})")
    fit1 = ssr.fit_size_effect(hs, [ssr.sel(h, 4e6, 0.03, 1.0) for h in hs], r_fixed=1.0)
    check(fit1 is not None and abs(fit1["D_b_m"] / 0.03 - 1) < 1e-6 and fit1["rms_log_residual"] < 1e-9,
          "the r = 1 fit recovers its law")

    # 4. A tiny series end to end: two depths, a plain and a reinforced beam each, coarse particles
    # and fast loading (not a prediction: the pipeline).
    tiny = os.path.join(tmp, "tiny")
    subprocess.run([sys.executable, GENERATOR, "--out", tiny, "--quick-only", "--depths", "0.1,0.2",
                    "--ratios", "0,1.05", "--coarsen", "3", "--velocity", "0.2"],
                   check=True, capture_output=True, cwd=source)
    study = os.path.join(tmp, "study")
    r = subprocess.run([rcdem, "-q", "study", "size_series", "--scenarios",
                        os.path.join(tiny, "quick"), "-o", study],
                       capture_output=True, text=True, timeout=900)
    check(r.returncode == 0, f"rcdem study size_series on the tiny series exits 0 ({r.stderr.strip()[-300:]})")
    rep = json.load(open(os.path.join(study, "size_effect.json"))) if r.returncode == 0 else {}
    cells = {(c["h_m"], round(c["rho_percent"], 2)): c for c in rep.get("cells", [])}
    check(sorted(cells) == [(0.1, 0.0), (0.1, 1.05), (0.2, 0.0), (0.2, 1.05)],
          f"the report has one cell per depth and ratio ({sorted(cells)})")
    plain = cells.get((0.1, 0.0))
    if plain:
        # sigma_N = 3 P L / (2 b h^2) of the run's own peak.
        peak = plain["peak_N"]["mean"]
        check(abs(plain["sigma_N_Pa"]["mean"] - 3 * peak * 0.6 / (2 * 0.15 * 0.01)) < 1e-6 * peak,
              "sigma_N is 3 P L / (2 b h^2)")
    check(rep.get("fit_r_1") is not None and len(rep.get("rho_min", [])) == 2,
          "the r = 1 fit and one rho_min row per depth are reported")
    outs = ["size_series.md", "sigma_n_vs_h.png", "rho_min_vs_h.png", "load_deflection_h100.png",
            "load_deflection_h200.png"]
    check(all(os.path.exists(os.path.join(study, f)) for f in outs), f"{', '.join(outs)} written")

checks.finish()
