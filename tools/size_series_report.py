#!/usr/bin/python3
"""The size series' report (`rcdem study size_series`, docs/size-series.md) from a study
directory, or one report over several (-o OUT DIR...): per depth h and steel ratio, the peak load
and the nominal strength sigma_N = 3 P L / (2 b h^2) over the packings (mean, sd, range), the
supports' peak beside the plate's, the brittle/ductile class of every run by the case study's
criterion (docs/model.md 10), and:
  - Bazant's type-1 size-effect law sigma_N = f_r_inf (1 + r D_b / h)^(1/r) fitted to the plain
    beams (every packing a point; r free and r = 1), with residuals;
  - the minimum ductile ratio rho_min(h) (the smallest ratio from which every larger ratio's runs
    are ductile on most packings) and Carpinteri's brittleness number
    N_P = rho f_y h^(1/2) / K_IC at it, K_IC = sqrt(E G_F) with E = 34.2 GPa (Table 1) and G_F the
    plain beams' damage energy over their ligament b h;
  - figures: sigma_N-h (log-log, with the fits), load-deflection per size, rho_min-h.
Writes into the (first) study directory, or OUT: size_series.md, size_effect.json,
sigma_n_vs_h.png, load_deflection_h<mm>.png, rho_min_vs_h.png. SI in files; plot axes in mm, MPa
and kN.

usage: size_series_report.py STUDY_DIR
       size_series_report.py -o OUT_DIR STUDY_DIR [STUDY_DIR ...]
"""
import json
import math
import os
import sys
import tomllib

import matplotlib
import matplotlib.ticker

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from scipy.optimize import least_squares  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import study_ensemble as ens  # noqa: E402
import study_report as sr  # noqa: E402

E_TABLE1 = 34.2e9        # Pa (Table 1)
SIGMA_T = 4.0e6          # Pa (Table 1): where f_r_inf should sit


def beam_of(case_dir):
    """Depth, width, span, steel ratio A_s / (b h) and f_y of a run, from its scenario.toml."""
    with open(os.path.join(case_dir, "scenario.toml"), "rb") as f:
        s = tomllib.load(f)
    _, b, h = s["specimen"]["size"]
    plates = s.get("plates", {})
    centre = lambda p: (p["extent"][0] + p["extent"][1]) / 2  # noqa: E731
    span = abs(centre(plates["support_right"]) - centre(plates["support_left"]))
    bars = list(s.get("bars", {}).values())
    area = sum(math.pi * bar["diameter"] ** 2 / 4 for bar in bars)
    fy = bars[0]["f_y"] if bars else None
    return dict(h=h, b=b, span=span, rho=area / (b * h), f_y=fy,
                bars=f"{len(bars)}Φ{bars[0]['diameter'] * 1e3:g}" if bars else "none")


def read_run(case_dir):
    rows = sr.history(case_dir)
    d, p = sr.curve(case_dir, rows)
    rs = sr.reactions(case_dir, rows)
    beam = beam_of(case_dir)
    beh = sr.behaviour(d, p)
    summary = json.load(open(os.path.join(case_dir, "summary.json")))
    peak = float(np.max(p))
    run = dict(beam, d=d, p=p, peak_N=peak, behaviour=beh, cls=beh["class"].split()[0],
               sigma_n=3 * peak * beam["span"] / (2 * beam["b"] * beam["h"] ** 2),
               reaction_peak_N=None if rs is None else float(np.max(rs)),
               damage_J=float(rows[-1]["dissipated_damage_J"]), steps=summary.get("steps"),
               wall_s=summary.get("seconds"), commit=summary.get("rcdem", {}).get("git_hash"))
    return run


def read_runs(studies):
    runs = []
    for study in studies:
        for row in sr.read_csv(os.path.join(study, "cases.csv")):
            if row["status"] != "finished":
                continue
            run = read_run(sr.run_path(study, row))
            run.update(case=row["case"], seed=int(row["seed"]))
            runs.append(run)
    return runs


def sel(h, f_inf, d_b, r):
    return f_inf * (1 + r * d_b / h) ** (1 / r)


def fit_size_effect(hs, sigmas, r_fixed=None):
    """Least squares on log sigma_N; None when fewer points than parameters, or no convergence."""
    hs, sigmas = np.asarray(hs), np.asarray(sigmas)
    n_par = 2 if r_fixed is not None else 3
    if len(set(hs)) < 2 or len(hs) < n_par + (0 if r_fixed is not None else 1):
        return None

    def residual(x):
        r = r_fixed if r_fixed is not None else x[2]
        return np.log(sel(hs, x[0], x[1], r)) - np.log(sigmas)

    x0 = [min(sigmas), 0.5 * min(hs)] + ([] if r_fixed is not None else [1.0])
    lo = [1e3, 1e-6] + ([] if r_fixed is not None else [0.05])
    hi = [1e9, 100.0] + ([] if r_fixed is not None else [20.0])
    res = least_squares(residual, x0, bounds=(lo, hi), x_scale=[1e6, 0.1] + ([1.0] if n_par == 3 else []))
    if not res.success:
        return None
    r = r_fixed if r_fixed is not None else float(res.x[2])
    fitted = sel(hs, res.x[0], res.x[1], r)
    # A parameter on its bound is not identified by these sizes (the law's curvature needs a wider
    # range of h than the scatter allows).
    at_bound = [name for name, v, a, b in zip(("f_r_inf", "D_b", "r"), res.x, lo, hi)
                if not a * (1 + 1e-3) < v < b * (1 - 1e-3)]
    return dict(f_r_inf_Pa=float(res.x[0]), D_b_m=float(res.x[1]), r=r, r_free=r_fixed is None,
                at_bound=at_bound,
                rms_log_residual=float(np.sqrt(np.mean(res.fun ** 2))),
                residuals=[dict(h_m=float(h), sigma_N_Pa=float(s), fit_Pa=float(f),
                                relative=float(s / f - 1)) for h, s, f in zip(hs, sigmas, fitted)])


def groups(runs):
    """{(h, nominal ratio key): [runs]} with the ratio rounded to 0.01% (one layout per cell)."""
    out = {}
    for r in runs:
        out.setdefault((r["h"], round(100 * r["rho"], 2)), []).append(r)
    return dict(sorted(out.items()))


def rho_min(cells, h):
    """The smallest achieved ratio at depth h from which every larger ratio is ductile on more
    than half of its packings, and the largest ratio below it (brittle), or None."""
    ratios = sorted(k[1] for k in cells if k[0] == h and k[1] > 0)
    ductile = {q: sum(r["cls"] == "ductile" for r in cells[(h, q)]) > len(cells[(h, q)]) / 2
               for q in ratios}
    found, below = None, None
    for i, q in enumerate(ratios):
        if all(ductile[x] for x in ratios[i:]):
            found = q
            below = ratios[i - 1] if i > 0 else 0.0
            break
    if found is None:
        return None
    run = cells[(h, found)][0]
    below_rho = 100 * cells[(h, below)][0]["rho"] if below else 0.0
    return dict(rho_percent=100 * run["rho"], rho_below_percent=below_rho, f_y_Pa=run["f_y"],
                bars=run["bars"])


def cell_stats(rs):
    peaks = [r["peak_N"] for r in rs]
    return dict(seeds=[r["seed"] for r in rs], bars=rs[0]["bars"], rho_percent=100 * rs[0]["rho"],
                peak_N=ens.describe(peaks), sigma_N_Pa=ens.describe([r["sigma_n"] for r in rs]),
                reaction_peak_N=ens.describe([r["reaction_peak_N"] for r in rs
                                              if r["reaction_peak_N"] is not None]),
                plate_over_supports=[r["peak_N"] / r["reaction_peak_N"] for r in rs
                                     if r["reaction_peak_N"]],
                classes=[r["cls"] for r in rs], steps=[r["steps"] for r in rs],
                wall_s=[r["wall_s"] for r in rs])


def analyse(runs):
    cells = groups(runs)
    plain = [r for r in runs if r["rho"] == 0]
    hs = sorted({r["h"] for r in runs})
    g_f = [r["damage_J"] / (r["b"] * r["h"]) for r in plain]
    k_ic = math.sqrt(E_TABLE1 * float(np.mean(g_f))) if g_f else None
    report = dict(depths_m=hs, commits=sorted({str(r["commit"]) for r in runs}),
                  cells=[dict(h_m=k[0], **cell_stats(v)) for k, v in cells.items()],
                  fit_r_free=fit_size_effect([r["h"] for r in plain], [r["sigma_n"] for r in plain]),
                  fit_r_1=fit_size_effect([r["h"] for r in plain], [r["sigma_n"] for r in plain], 1.0),
                  G_F_J_per_m2=ens.describe(g_f) if g_f else None, K_IC_Pa_sqrt_m=k_ic,
                  rho_min=[])
    for h in hs:
        m = rho_min(cells, h)
        if m is not None:
            m["N_P"] = (m["rho_percent"] / 100 * m["f_y_Pa"] * math.sqrt(h) / k_ic) if k_ic else None
        report["rho_min"].append(dict(h_m=h, **(m or {})))
    return report, cells


def finish(fig, ax, xlabel, ylabel, path):
    """Labels, a legend, and the figure written to path."""
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def plot_sigma_n(report, cells, out):
    fig, ax = plt.subplots(figsize=(5.5, 4.2))
    plain = [(k[0], r["sigma_n"]) for k, v in cells.items() if k[1] == 0 for r in v]
    if plain:
        ax.plot([h * 1e3 for h, _ in plain], [s / 1e6 for _, s in plain], "o", color="tab:blue",
                alpha=0.6, label="plain beams (each packing)")
    hh = np.geomspace(0.05, 1.0, 100)
    for key, style, name in (("fit_r_free", "-", "type-1 law, r free"), ("fit_r_1", "--", "type-1 law, r = 1")):
        f = report[key]
        if f:
            ax.plot(hh * 1e3, sel(hh, f["f_r_inf_Pa"], f["D_b_m"], f["r"]) / 1e6, style, color="black",
                    label=f"{name}: f∞ = {f['f_r_inf_Pa'] / 1e6:.2f} MPa, D_b = {f['D_b_m'] * 1e3:.0f} mm, r = {f['r']:.2f}")
    ax.axhline(SIGMA_T / 1e6, color="grey", lw=0.8, ls=":", label="σt of Table 1")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xticks([50, 100, 200, 400, 1000])
    ax.xaxis.set_major_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
    ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    ax.yaxis.set_major_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
    ax.yaxis.set_minor_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
    finish(fig, ax, "depth h [mm]", "nominal strength σN = 3PL/(2bh²) [MPa]",
           os.path.join(out, "sigma_n_vs_h.png"))


def plot_curves(report, cells, out):
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for h in report["depths_m"]:
        fig, ax = plt.subplots(figsize=(5.5, 4.2))
        for i, (k, rs) in enumerate((k, v) for k, v in cells.items() if k[0] == h):
            for j, r in enumerate(rs):
                ax.plot(r["d"] * 1e3, r["p"] / 1e3, color=colours[i % len(colours)], lw=0.9,
                        label=f"ρ = {k[1]:.2f}% ({r['bars']})" if j == 0 else None)
        ax.set_title(f"h = {h * 1e3:g} mm")
        finish(fig, ax, "midspan deflection [mm]", "load [kN]",
               os.path.join(out, f"load_deflection_h{h * 1e3:g}.png"))


def plot_rho_min(report, out):
    pts = [m for m in report["rho_min"] if "rho_percent" in m]
    fig, ax = plt.subplots(figsize=(5.5, 4.2))
    if pts:
        h = np.array([m["h_m"] for m in pts])
        hi = np.array([m["rho_percent"] for m in pts])
        lo = np.array([m["rho_below_percent"] for m in pts])
        ax.errorbar(h * 1e3, hi, yerr=[hi - lo, 0 * hi], fmt="s", capsize=3,
                    label="ρ_min (bar: down to the largest brittle ratio)")
        hh = np.geomspace(h.min(), h.max(), 50)
        ax.plot(hh * 1e3, hi[0] * np.sqrt(h[0] / hh), ":", color="grey", label="∝ h^-½ (N_P constant)")
    ax.set_xscale("log")
    finish(fig, ax, "depth h [mm]", "minimum ductile steel ratio [%]",
           os.path.join(out, "rho_min_vs_h.png"))


def fit_lines(f, name):
    if not f:
        return [f"- {name}: not enough plain beams to fit."]
    lines = [f"- {name}: f_r∞ = {f['f_r_inf_Pa'] / 1e6:.3f} MPa ({f['f_r_inf_Pa'] / SIGMA_T:.2f} σt), "
             f"D_b = {f['D_b_m'] * 1e3:.1f} mm, r = {f['r']:.2f}; rms of log residuals "
             f"{f['rms_log_residual']:.4f}"
             + (f"; **{', '.join(f['at_bound'])} at the fit's bound: not identified by these data**"
                if f.get("at_bound") else "")
             + "; residuals (σN / fit − 1): "
             + ", ".join(f"h {x['h_m'] * 1e3:g}: {100 * x['relative']:+.1f}%" for x in f["residuals"])]
    return lines


def spread(e, scale, digits):
    """mean ± sd (min–max), or the one value."""
    if e["n"] == 1:
        return f"{e['mean'] / scale:.{digits}f}"
    return (f"{e['mean'] / scale:.{digits}f} ± {e['sd'] / scale:.{digits}f} "
            f"({e['min'] / scale:.{digits}f}–{e['max'] / scale:.{digits}f})")


def markdown(report):
    lines = ["# Size series", "",
             f"{sum(len(c['seeds']) for c in report['cells'])} runs by rcdem "
             f"{', '.join(report['commits'])} (tools/size_series_report.py; SI in size_effect.json). "
             "Per depth and steel ratio, over the packings.", "",
             "| h [mm] | ρ [%] | bars | packings | peak [kN] mean ± sd (range) | σN [MPa] mean ± sd (range) | "
             "supports' peak [kN] | plate ÷ supports | classes |", "|---|---|---|---|---|---|---|---|---|"]
    for c in report["cells"]:
        pk, sn, rp = c["peak_N"], c["sigma_N_Pa"], c["reaction_peak_N"]
        ratio = c["plate_over_supports"]
        lines.append(
            f"| {c['h_m'] * 1e3:g} | {c['rho_percent']:.3f} | {c['bars']} | {len(c['seeds'])} | "
            f"{spread(pk, 1e3, 2)} | {spread(sn, 1e6, 3)} | "
            + (f"{rp['mean'] / 1e3:.2f}" if rp else "–") + " | "
            + (f"{min(ratio):.3f}" + (f"–{max(ratio):.3f}" if max(ratio) > min(ratio) else "")
               + (" **(> 2%)**" if max(abs(x - 1) for x in ratio) > 0.02 else "")
               if ratio else "–")
            + " | " + ", ".join(c["classes"]) + " |")
    lines += ["", "## Size effect of the plain beams (Bažant's type-1 law on σN)", ""]
    lines += fit_lines(report["fit_r_free"], "r free") + fit_lines(report["fit_r_1"], "r = 1")
    gf = report["G_F_J_per_m2"]
    lines += ["", "## Minimum ductile ratio and brittleness number", ""]
    if gf:
        lines.append(f"G_F = damage energy of the plain beams / (b h) = {gf['mean']:.1f} J/m² "
                     f"(range {gf['min']:.1f}–{gf['max']:.1f}, {gf['n']} runs); K_IC = √(E G_F) = "
                     f"{report['K_IC_Pa_sqrt_m'] / 1e6:.3f} MPa√m with E = 34.2 GPa.")
    lines += ["", "| h [mm] | ρ_min [%] | bars | largest brittle ratio below [%] | N_P = ρ f_y √h / K_IC |",
              "|---|---|---|---|---|"]
    for m in report["rho_min"]:
        if "rho_percent" in m:
            n_p = f"{m['N_P']:.3f}" if m.get("N_P") is not None else "–"
            lines.append(f"| {m['h_m'] * 1e3:g} | {m['rho_percent']:.3f} | {m['bars']} | "
                         f"{m['rho_below_percent']:.3f} | {n_p} |")
        else:
            lines.append(f"| {m['h_m'] * 1e3:g} | none ductile | | | |")
    return "\n".join(lines) + "\n"


def main(studies, out):
    runs = read_runs(studies)
    if not runs:
        sys.exit(f"size_series_report: no finished run in {', '.join(studies)}")
    report, cells = analyse(runs)
    os.makedirs(out, exist_ok=True)
    plot_sigma_n(report, cells, out)
    plot_curves(report, cells, out)
    plot_rho_min(report, out)
    with open(os.path.join(out, "size_effect.json"), "w") as f:
        json.dump(report, f, indent=1)
    with open(os.path.join(out, "size_series.md"), "w") as f:
        f.write(markdown(report))
    print(f"size series report: {len(runs)} runs, written to {out}")


if __name__ == "__main__":
    args = sys.argv[1:]
    if len(args) >= 3 and args[0] == "-o":
        main(args[2:], args[1])
    elif len(args) == 1 and not args[0].startswith("-"):
        main(args, args[0])
    else:
        sys.exit(__doc__)
