#!/usr/bin/python3
"""The tables of docs/calibration.md from `rcdem calibrate` output directories, so that they are
regenerated rather than edited by hand.

usage:
  calibration_tables.py results DIR [DIR ...]   one row per directory: cube, seed, E, nu, strengths
  calibration_tables.py search DIR              the iterations of a search (--target)
  calibration_tables.py details DIR [DIR ...]   per directory: strains at the peaks, nu at 40%
                                                of the compressive peak, energy balances, steps

Every row names the rcdem build that ran it (summary.json of its compression test).
"""
import json
import os
import sys

TARGET = {"E": 34.2e9, "nu": 0.15, "sigma_c": 91.2e6, "sigma_t": 4.0e6}


def load(d):
    with open(os.path.join(d, "calibration.json")) as f:
        return json.load(f)


def test_dir(d):
    """The directory of the final pair's compression test (a search keeps it in final/)."""
    for sub in ("final/compression", "compression"):
        if os.path.exists(os.path.join(d, sub, "summary.json")):
            return os.path.join(d, sub)
    raise SystemExit(f"{d}: no compression test")


def misfit(m, k):
    return f"{100 * (m[k] / TARGET[k] - 1):+.1f}%"


def results(dirs):
    print("| cube | seed | particles | E (GPa) | ν | σc (MPa) | σt (MPa) | σc/σt | E, ν on the face "
          "gauges | kinetic/strain at the peaks | rcdem |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for d in dirs:
        c = load(d)
        m = c["measured"]
        s = json.load(open(os.path.join(test_dir(d), "summary.json")))
        build = s.get("rcdem", {})
        print(f"| {1e3 * c['cube_size_m']:.0f} mm | {c['seed']} | {s['specimen']['particles']['total']:,} | "
              f"{m['E'] / 1e9:.2f} ({misfit(m, 'E')}) | {m['nu']:.4f} ({misfit(m, 'nu')}) | "
              f"{m['sigma_c'] / 1e6:.2f} ({misfit(m, 'sigma_c')}) | "
              f"{m['sigma_t'] / 1e6:.3f} ({misfit(m, 'sigma_t')}) | {m['sigma_c_over_sigma_t']:.1f} | "
              f"{m['E_face_gauge'] / 1e9:.2f} GPa, {m['nu_face_gauge']:.4f} | "
              f"{m['kinetic_over_strain_at_peak_compression']:.1e}, "
              f"{m['kinetic_over_strain_at_peak_tension']:.1e} | "
              f"{build.get('git_hash', '?')} |")


def details(dirs):
    for d in dirs:
        c = load(d)
        m = c["measured"]
        runs = [json.load(open(os.path.join(os.path.dirname(test_dir(d)), t, "summary.json")))
                for t in ("compression", "tension")]
        print(f"{1e3 * c['cube_size_m']:.0f} mm cube, seed {c['seed']}: strain at the peak "
              f"{1e3 * m['strain_at_peak_compression']:.2f}‰ (compression), "
              f"{1e3 * m['strain_at_peak_tension']:.3f}‰ (tension); ν at 40% of the "
              f"compressive peak {m['nu_at_40_percent_compression']:.2f}; energy balance "
              f"{100 * m['energy_balance_error_compression']:.2g}% (compression), "
              f"{100 * m['energy_balance_error_tension']:.2g}% (tension); "
              f"{runs[0]['steps']:,} and {runs[1]['steps']:,} steps, "
              f"{runs[0]['seconds']:.0f} and {runs[1]['seconds']:.0f} s")


def search(d):
    c = load(d)
    print(f"Search on the {1e3 * c['cube_size_m']:.0f} mm cube, seed {c['seed']}, tolerance "
          f"{100 * c['tolerance']:.0f}%: {'converged' if c['converged'] else 'not converged'}; "
          f"chosen iteration {c.get('chosen_iteration')}; tension lever "
          f"{c.get('tension_lever', 'sigma_nt')}.")
    print()
    print("| iteration | Ē (GPa) | α | σ_n,t (MPa) | τ (MPa) | G_f,n (J/m²) | E (GPa) | ν | σc (MPa) | "
          "σt (MPa) | worst misfit |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for i, it in enumerate(c["iterations"]):
        p, m = it["parameters"], it["measured"]
        print(f"| {i} | {p['E_bar'] / 1e9:.2f} | {p['alpha']:.4f} | {p['sigma_nt'] / 1e6:.3f} | "
              f"{p['tau'] / 1e6:.2f} | {p['G_fn']:.3f} | {m['E'] / 1e9:.2f} | {m['nu']:.4f} | {m['sigma_c'] / 1e6:.2f} | "
              f"{m['sigma_t'] / 1e6:.3f} | {100 * it['worst_misfit']:.1f}% |")


if __name__ == "__main__":
    if len(sys.argv) < 3 or sys.argv[1] not in ("results", "details", "search"):
        sys.exit(__doc__)
    if sys.argv[1] == "search":
        search(sys.argv[2])
    else:
        (results if sys.argv[1] == "results" else details)(sys.argv[2:])
