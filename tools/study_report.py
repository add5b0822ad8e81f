#!/usr/bin/python3
"""Tables and figures of the three-point bending study (paper 3, SPEC 10) from a study directory.

usage: study_report.py STUDY_DIR
       study_report.py -o OUT_DIR STUDY_DIR [STUDY_DIR ...]

Reads STUDY_DIR/cases.csv and each finished case's run directory (STUDY_DIR/cases/<case>/:
summary.json, history.csv, broken_points.csv, the last snapshots) and writes into STUDY_DIR, or
with -o one report over the finished runs of several study directories (each (case, seed) in one
of them only; cases.csv and peak_loads.csv there are theirs, with a column `study`) into OUT_DIR:
  curves/<case>.csv           load-midspan deflection curve (deflection_m, load_N)
  figure10_<model>.png        EL, NL-A, NL-B curves of one beam, experimental peak marked (Fig. 10)
  figure10f_NL-B.png          every beam's NL-B curve (and AN0) (Fig. 10 f)
  figure9_<case>.png          crack pattern: damaged facets seen on the side face (Fig. 9)
  figure8_<case>.png          deformed shape, displacements x20 (Fig. 8)
  crack_height.png            height of the highest broken point near midspan vs deflection
  table3.md                   peak loads beside the paper's Table 3, and the behaviour checks
  report.json                 every number of table3.md, for tests and docs
Where a run is not one of the paper's beams as the paper ran it (a case not named after a model
of Table 3, another set-up, or a swept key: `rcdem study --sweep`), the report is generic:
  curves/<run>.csv            load-displacement curve (displacement_m, load_N)
  load_displacement.png       every run's curve, each labelled with its run directory
  cases.md                    per run: case, swept value, seed, peak, displacement at peak, stop
  report.json                 the same numbers
Lengths in files are SI; plot axes are labelled in mm and kN.
"""
import csv
import json
import math
import os
import shutil
import sys
import tempfile
import xml.etree.ElementTree as ET

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import study_ensemble as ens  # noqa: E402

# SPEC 10 / paper Table 3: bars, f_y [MPa], P_exp, P_paper EL, NL-A, NL-B [kN].
TABLE3 = {
    "AN0": ("none", None, 11.8, 11.7, None, None),
    "AN1": ("1Φ4", 637, 11.9, 13.6, 11.0, 11.0),
    "AN2": ("2Φ5", 569, 15.2, 26.8, 16.4, 16.3),
    "AN3": ("2Φ8", 441, 27.9, 38.9, 33.2, 30.7),
    "AN4": ("2Φ10", 456, 48.7, 43.8, 39.1, 36.0),
}
MODELS = list(TABLE3)  # in order of steel
BARS = {"AN0": (0, 0.0), "AN1": (1, 0.004), "AN2": (2, 0.005), "AN3": (2, 0.008), "AN4": (2, 0.010)}
INTERFACES = ("EL", "NL-A", "NL-B")
COLOURS = {"EL": "tab:blue", "NL-A": "tab:orange", "NL-B": "tab:green", "none": "black"}

# Beam (SPEC 10); the calibrated concrete's *elastic* E and nu for the Timoshenko stiffness (K0 is
# read before any local point breaks): the 160 mm cube, seed 1, interior gauge, under the elastic
# law (examples/uniaxial/cube160_elastic.toml, tools/elastic_moduli.py, docs/case-study.md), not
# the calibration's secant at 40% of the compressive peak (33.98 GPa), which lateral
# microcracking has already softened; steel E of the bars (SPEC 7).
SPAN, B, H, LENGTH = 0.600, 0.150, 0.100, 0.700
BAR_Z = H / 10
E_CONCRETE, NU_CONCRETE, E_STEEL = 35.19e9, 0.1561, 200e9

# Cracking load: the largest load before the load first falls by this fraction below its running
# maximum (a crack through the tension zone; smaller wiggles are single facets breaking).
DROP = 0.15
RECOVERY_FACTOR = 2.0


def read_csv(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def history(case_dir):
    return read_csv(os.path.join(case_dir, "history.csv"))


def curve(case_dir, rows=None):
    """(deflection, load) per history row of a run (rows: its history.csv, if already read)."""
    rows = history(case_dir) if rows is None else rows
    summary = os.path.join(case_dir, "summary.json")  # absent while a run is going
    s = json.load(open(summary)) if os.path.exists(summary) else {}
    column = s.get("displacement_column") or f"{s.get('control', 'load')}_displacement_m"
    d = np.array([abs(float(r[column])) for r in rows])
    p = np.array([float(r["load_N"]) for r in rows])
    return d, p


def reactions(case_dir, rows=None):
    """The sum of the supports' reactions at each history row (the load the beam carries), or None
    when the case has no plates of those names. In a quasi-static test it equals the loading
    plate's force; a spike of the plate's force that the reactions do not follow is a local,
    dynamic event under the plate."""
    rows = history(case_dir) if rows is None else rows
    if not rows or "support_left_force_N" not in rows[0] or "support_right_force_N" not in rows[0]:
        return None
    return np.array([abs(float(r["support_left_force_N"]) + float(r["support_right_force_N"]))
                     for r in rows])


def by_interface(model, got, pexp):
    """A beam's peaks by interface (AN0's one case under EL), NL-B's error against the experiment
    (AN0: its case's) and whether EL >= NL-A >= NL-B (None where a case is missing)."""
    mine = {"EL": got.get("none")} if model == "AN0" else {i: got.get(i) for i in INTERFACES}
    nlb = mine.get("NL-B") if model != "AN0" else mine.get("EL")
    err = None if nlb is None else nlb / (pexp * 1e3) - 1
    vals = [mine.get(i) for i in INTERFACES]
    order = None
    if model != "AN0" and all(v is not None for v in vals):
        order = vals[0] >= vals[1] >= vals[2]
    return mine, err, order


def timoshenko_stiffness(model, span=SPAN):
    """Midspan stiffness P/delta of a simply supported beam under a central load, uncracked
    transformed section (steel as (n - 1) A_s of concrete at the bars' height), kappa = 5/6."""
    count, dia = BARS[model]
    n = E_STEEL / E_CONCRETE
    a_s = count * math.pi * dia ** 2 / 4
    area = B * H + (n - 1) * a_s
    zc = (B * H * H / 2 + (n - 1) * a_s * BAR_Z) / area
    inertia = B * H ** 3 / 12 + B * H * (H / 2 - zc) ** 2 + (n - 1) * a_s * (zc - BAR_Z) ** 2
    shear = E_CONCRETE / (2 * (1 + NU_CONCRETE))
    flex = span ** 3 / (48 * E_CONCRETE * inertia)
    shear_c = span / (4 * (5 / 6) * shear * B * H)
    return 1 / (flex + shear_c), 1 / flex


def behaviour(d, p):
    """Cracking load (first local maximum followed by a drop of DROP), peak, and whether the load
    recovers above the cracking load afterwards (ductile) or not (brittle)."""
    peak_i = int(np.argmax(p))
    crack_i = None
    for i in range(1, len(p)):
        if p[i] <= 0:
            continue
        running_max_i = int(np.argmax(p[: i + 1]))
        if p[i] < (1 - DROP) * p[running_max_i]:
            crack_i = running_max_i
            break
    if crack_i is None:
        return {"cracking_load_N": None, "cracking_deflection_m": None,
                "peak_load_N": float(p[peak_i]), "deflection_at_peak_m": float(d[peak_i]),
                "recovers": None, "class": "ductile (no drop)"}
    p_cr = float(p[crack_i])
    # Ductile: once the deflection is past twice the cracking deflection (the crack has opened and
    # the steel carries the tension), the load climbs back above the cracking load. A brief
    # recovery within the cracking event itself (a second facet cluster holding on) does not
    # count; a run ended by the load drop has nothing past it: brittle.
    later = p[d >= RECOVERY_FACTOR * d[crack_i]]
    drop_i = crack_i + 1 + int(np.argmin(p[crack_i + 1:])) if crack_i + 1 < len(p) else crack_i
    recovers = bool(later.size and np.any(later > p_cr))
    return {"cracking_load_N": p_cr, "cracking_deflection_m": float(d[crack_i]),
            "peak_load_N": float(p[peak_i]), "deflection_at_peak_m": float(d[peak_i]),
            "post_peak_min_N": float(p[drop_i]), "recovers": recovers,
            "class": "ductile" if recovers else "brittle"}


# K0 is read from rows where the kinetic energy is below this fraction of the strain energy. At the
# study's rates no row of the elastic window qualifies: the beam moving at the plate's speed
# carries kinetic energy ~ v^2 while the strain energy grows ~ deflection^2 (full AN0: kinetic /
# strain 0.46 -> 0.16 over the window; docs/case-study.md). K0 is then read over all the window's
# rows and flagged, with the window's kinetic/strain range and its largest imbalance between the
# loading plate and the supports (the inertial force, which a steady motion does not have).
K0_KINETIC_LIMIT = 0.05


def energy_rows(case_dir, p, rs, rows=None):
    """Per history row: kinetic / strain energy, and |plate load p - supports' reactions rs| / load
    (NaN without the supports' columns, rs None)."""
    rows = history(case_dir) if rows is None else rows
    ratio = np.array([float(r["kinetic_J"]) / float(r["strain_J"]) if float(r["strain_J"]) > 0
                      else np.inf for r in rows])
    load = np.abs(p)
    imbalance = (np.abs(load - rs) / np.maximum(load, 1e-30) if rs is not None
                 else np.full(len(rows), np.nan))
    return ratio, imbalance


def initial_stiffness(d, p, p_ref, kinetic_over_strain, imbalance):
    """Least-squares slope of load on deflection between 10% and 40% of p_ref (the load at which
    the first local point broke: still elastic), through the first crossing of 40%, over the
    quasi-static rows (kinetic < K0_KINETIC_LIMIT of the strain energy) if at least 3 qualify,
    else over all the window's rows. Returns (K0 or None, quasi-static?, kinetic/strain range,
    largest plate/support imbalance) for the report."""
    if p_ref is None or p_ref <= 0:
        p_ref = float(np.max(p))
    end = int(np.argmax(p >= 0.4 * p_ref))
    window = [i for i in range(end + 1) if 0.1 * p_ref <= p[i] <= 0.4 * p_ref]
    qs = [i for i in window if kinetic_over_strain[i] < K0_KINETIC_LIMIT]
    sel, quasi_static = (qs, True) if len(qs) >= 3 else (window, False)
    if len(sel) < 3:
        return None, False, None, None
    k0 = float(np.polyfit(d[sel], p[sel], 1)[0])
    ks = [float(kinetic_over_strain[i]) for i in sel]
    imb = [float(imbalance[i]) for i in sel if np.isfinite(imbalance[i])]
    return k0, quasi_static, [min(ks), max(ks)], (max(imb) if imb else None)


def last_snapshot(case_dir, series):
    pvd = os.path.join(case_dir, f"{series}.pvd")
    if not os.path.exists(pvd):
        return None, None
    files = [ds.get("file") for ds in ET.parse(pvd).getroot().iter("DataSet")]
    if not files:
        return None, None
    return os.path.join(case_dir, files[0]), os.path.join(case_dir, files[-1])


def beam_outline(ax):
    ax.plot([0, LENGTH * 1e3, LENGTH * 1e3, 0, 0], [0, 0, H * 1e3, H * 1e3, 0], "k-", lw=0.8)
    for xc in ((LENGTH - SPAN) / 2, (LENGTH + SPAN) / 2):
        ax.add_patch(plt.Rectangle(((xc - 0.01) * 1e3, -4), 20, 4, color="grey"))
    ax.add_patch(plt.Rectangle(((LENGTH / 2 - 0.01) * 1e3, H * 1e3), 20, 4, color="grey"))


def kept_figure(case, case_dir, out, number):
    """A run kept without its snapshots (tools/study_archive.py pack-runs) keeps its Figure 8 and
    9 as drawn from them, figure8.png and figure9.png: copied as the study's figure."""
    kept = os.path.join(case_dir, f"figure{number}.png")
    if not os.path.exists(kept):
        return None
    path = os.path.join(out, f"figure{number}_{case}.png")
    shutil.copyfile(kept, path)
    return path


def draw_run_figures(case, case_dir):
    """Figures 8 and 9 of one run, into its own directory as figure8.png and figure9.png, from its
    last snapshots (none where it has none). Returns the files written."""
    written = []
    with tempfile.TemporaryDirectory() as tmp:
        for number, draw, series in ((9, figure9, "facets"), (8, figure8, "particles")):
            if last_snapshot(case_dir, series)[1] is None:
                continue
            target = os.path.join(case_dir, f"figure{number}.png")
            shutil.move(draw(case, case_dir, tmp), target)
            written.append(target)
    return written


def figure9(case, case_dir, out):
    """Damaged facets near the side face y = 0 (within one aggregate size), seen along y."""
    import meshio
    from matplotlib.collections import PolyCollection

    _, last = last_snapshot(case_dir, "facets")
    if last is None:
        return kept_figure(case, case_dir, out, 9)
    m = meshio.read(last)
    polys, dmg = [], []
    for block, damage in zip(m.cells, m.cell_data["damage"]):
        for cell, dd in zip(block.data, damage):
            if dd <= 0.0:
                continue
            pts = m.points[cell]
            if pts[:, 1].mean() > 0.012:
                continue
            polys.append(pts[:, [0, 2]] * 1e3)
            dmg.append(dd)
    fig, ax = plt.subplots(figsize=(10, 2.4))
    if polys:
        order = np.argsort(dmg)
        pc = PolyCollection([polys[i] for i in order], array=np.array(dmg)[order], cmap="Reds",
                            clim=(0, 1), edgecolors="none")
        ax.add_collection(pc)
        fig.colorbar(pc, ax=ax, label="damage D", fraction=0.03)
    beam_outline(ax)
    ax.set_xlim(-5, LENGTH * 1e3 + 5)
    ax.set_ylim(-8, H * 1e3 + 8)
    ax.set_aspect("equal")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("z [mm]")
    ax.set_title(f"{case}: damaged facets within 12 mm of the side face (final state)")
    fig.tight_layout()
    path = os.path.join(out, f"figure9_{case}.png")
    fig.savefig(path, dpi=130)
    plt.close(fig)
    return path


def figure8(case, case_dir, out, scale=20.0):
    """Particles near the side face at x0 + 20 u, coloured by damage; bars likewise."""
    import meshio

    _, last = last_snapshot(case_dir, "particles")
    if last is None:
        return kept_figure(case, case_dir, out, 8)
    m = meshio.read(last)
    u = m.point_data["displacement"]
    x0 = m.points - u
    kind = m.point_data.get("kind")
    sel = x0[:, 1] < 0.02
    if kind is not None:
        sel &= np.asarray(kind).ravel() >= 0
    xd = (x0 + scale * u)[sel]
    fig, ax = plt.subplots(figsize=(10, 2.6))
    sc = ax.scatter(xd[:, 0] * 1e3, xd[:, 2] * 1e3, s=3, c=np.asarray(m.point_data["damage"])[sel],
                    cmap="viridis", vmin=0, vmax=1)
    fig.colorbar(sc, ax=ax, label="particle damage", fraction=0.03)
    first, lastb = last_snapshot(case_dir, "bars")
    if first and lastb and first != lastb:
        b0, b1 = meshio.read(first), meshio.read(lastb)
        bd = b0.points + scale * (b1.points - b0.points)
        for block in b1.cells:
            for cell in block.data:
                ax.plot(bd[cell, 0] * 1e3, bd[cell, 2] * 1e3, "k-", lw=1.5)
    ax.plot([0, LENGTH * 1e3, LENGTH * 1e3, 0, 0], [0, 0, H * 1e3, H * 1e3, 0], "k:", lw=0.6)
    ax.set_aspect("equal")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("z [mm]")
    ax.set_title(f"{case}: deformed shape, displacements x{scale:g} (particles within 20 mm "
                 "of the side face)")
    fig.tight_layout()
    path = os.path.join(out, f"figure8_{case}.png")
    fig.savefig(path, dpi=130)
    plt.close(fig)
    return path


def crack_growth(case_dir):
    """(deflection, height of the highest broken point within 100 mm of midspan) in the order
    the points broke."""
    path = os.path.join(case_dir, "broken_points.csv")
    if not os.path.exists(path):
        return [], []
    rows = read_csv(path)
    d, z, top = [], [], 0.0
    for r in rows:
        if abs(float(r["x_m"]) - LENGTH / 2) > 0.1:
            continue
        top = max(top, float(r["z_m"]))
        d.append(abs(float(r["deflection_m"])))
        z.append(top)
    return d, z


def k0_cell(v):
    """K0 in kN/mm; a dagger and the window's kinetic/strain range where no row was quasi-static."""
    k0 = v["initial_stiffness_N_per_m"]
    if k0 is None:
        return "–"
    if v.get("initial_stiffness_quasi_static"):
        return f"{k0 / 1e6:.1f}"
    lo, hi = v["initial_stiffness_kinetic_over_strain"]
    imb = v.get("initial_stiffness_plate_support_imbalance")
    extra = f", plate/supports ≤ {100 * imb:.0f}%" if imb is not None else ""
    return f"{k0 / 1e6:.1f}† (KE/SE {lo:.2f}–{hi:.2f}{extra})"


def fmt_kn(v):
    return "–" if v is None else f"{v / 1e3:.1f}"


def run_report(r, case_dir, rows, d, p):
    """One run's numbers: its behaviour, K0 against Timoshenko, crack heights, first yield (rows:
    its history.csv, read once)."""
    summary = json.load(open(os.path.join(case_dir, "summary.json")))
    beh = behaviour(d, p)
    # The run tracks the peak at every step; the history only samples it.
    beh["peak_load_N"] = summary.get("peak_load_N", beh["peak_load_N"])
    beh["deflection_at_peak_m"] = abs(summary.get("displacement_at_peak_m", beh["deflection_at_peak_m"]))
    first = summary.get("first_cracking") or {}
    rs = reactions(case_dir, rows)
    k0, k0_qs, k0_ke, k0_imb = initial_stiffness(
        d, p, first.get("load_N") or beh["cracking_load_N"], *energy_rows(case_dir, p, rs, rows))
    kt, kb = timoshenko_stiffness(r["model"])
    # The supports are 20 mm wide: once the beam bends it bears on their inner edges.
    kt_inner, _ = timoshenko_stiffness(r["model"], SPAN - 0.020)
    if rs is not None and len(rs):
        k = int(np.argmax(rs))
        beh["reaction_peak_N"] = float(rs[k])
        beh["deflection_at_reaction_peak_m"] = float(d[k])
    cd, cz = crack_growth(case_dir)
    peak_d = beh["deflection_at_peak_m"]
    at_peak = max([z for dd, z in zip(cd, cz) if dd <= peak_d], default=None)
    yielded = [float(x.get("yielded_nodes") or 0) for x in rows]
    return dict(
        beh, case=r["case"], seed=r["seed"], directory=r["directory"], model=r["model"],
        interface=r["interface"],
        wall_time_s=float(r["wall_time_s"] or 0), steps=int(r["steps"] or 0),
        stop_reason=r["stop_reason"], initial_stiffness_N_per_m=k0,
        initial_stiffness_quasi_static=k0_qs,
        initial_stiffness_kinetic_over_strain=k0_ke,
        initial_stiffness_plate_support_imbalance=k0_imb,
        timoshenko_stiffness_N_per_m=kt, bernoulli_stiffness_N_per_m=kb,
        timoshenko_stiffness_inner_span_N_per_m=kt_inner,
        first_cracking=summary.get("first_cracking"),
        first_yield_deflection_m=ens.first_yield_deflection(d, yielded),
        crack_height_at_peak_m=at_peak, crack_height_final_m=(cz[-1] if cz else None),
        energy_balance_error=summary.get("energy", {}).get("balance_error"))


def run_path(study, row):
    """A cases.csv row's run directory (a study written before --seeds has no `directory`)."""
    return os.path.join(study, "cases", row.get("directory") or row["case"])


def read_runs(study):
    """The finished runs of cases.csv, each with its seed, run directory (a study written before
    --seeds has neither column: each case its own directory, seed unknown) and path."""
    rows = [r for r in read_csv(os.path.join(study, "cases.csv")) if r["status"] == "finished"]
    for r in rows:
        r["directory"] = r.get("directory") or r["case"]
        r["seed"] = int(r["seed"]) if r.get("seed") not in (None, "") else None
        r["study"] = study
        r["path"] = run_path(study, r)
    return rows


def read_studies(studies):
    """The finished runs of several studies; a (case, seed) found in two of them is refused: the
    report would count one packing twice, or mix two runs of it."""
    runs, where = [], {}
    for study in studies:
        if not os.path.exists(os.path.join(study, "cases.csv")):
            sys.exit(f"{study}: no cases.csv (not a study directory, or its study has not run)")
        for r in read_runs(study):
            key = (r["case"], r["seed"], r.get("variant") or "")
            if key in where:
                seed = f"seed {r['seed']}" if r["seed"] is not None else "its own seed"
                sys.exit(f"{r['case']} on {seed} is in both {where[key]} and {study}: "
                         "a report takes each case and packing from one study only")
            where[key] = study
            runs.append(r)
    # In (case, seed) order whatever the order of the studies: the same runs, the same report.
    return sorted(runs, key=lambda r: (r["case"], r.get("variant") or "",
                                       -1 if r["seed"] is None else r["seed"]))


def write_merged_tables(out, studies):
    """cases.csv and peak_loads.csv of several studies in one, each row naming its study (and in
    cases.csv the commit that ran it)."""
    for name in ("cases.csv", "peak_loads.csv"):
        rows = []
        for study in studies:
            path = os.path.join(study, name)
            for row in (read_csv(path) if os.path.exists(path) else []):
                row = {"study": os.path.abspath(study), **row}
                if name == "cases.csv":
                    row["commit"] = commit_of([{"path": run_path(study, row)}]).removeprefix("commit ")
                rows.append(row)
        if rows:
            with open(os.path.join(out, name), "w", newline="") as f:
                w = csv.DictWriter(f, fieldnames=list(rows[0]), lineterminator="\n")
                w.writeheader()
                w.writerows(rows)


def ensembles(report, data):
    """Per case over its packings: mean, sd and range of the peak, its deflection and the
    pre-yield load (read at one deflection per beam, study_ensemble.pre_yield_deflection)."""
    pre = {}
    for model in TABLE3:
        runs = [(data[k][0], v["first_yield_deflection_m"]) for k, v in report["cases"].items()
                if v["model"] == model and v["interface"] != "none"]
        pre[model] = ens.pre_yield_deflection(runs) if runs else None
    out = {}
    for k, v in report["cases"].items():
        at = pre.get(v["model"])
        v["pre_yield_deflection_m"] = at
        v["pre_yield_load_N"] = ens.load_near(*data[k], at) if at else None
    for case in sorted({v["case"] for v in report["cases"].values()}):
        runs = sorted((v for v in report["cases"].values() if v["case"] == case),
                      key=lambda v: (v["seed"] is None, v["seed"]))
        out[case] = {"model": runs[0]["model"], "interface": runs[0]["interface"],
                     "seeds": [v["seed"] for v in runs], "directories": [v["directory"] for v in runs],
                     "pre_yield_deflection_m": runs[0]["pre_yield_deflection_m"]}
        for key in ("peak_load_N", "deflection_at_peak_m", "pre_yield_load_N",
                    "reaction_peak_N", "wall_time_s", "steps", "energy_balance_error"):
            out[case][key] = ens.describe([v.get(key) for v in runs])
    report["ensembles"] = out


def orderings(report):
    """EL >= NL-A >= NL-B per reinforced beam, on the peak and on the pre-yield load, each pair
    by the paired test over the packings both cases ran on."""
    result = {}
    for model in TABLE3:
        if model == "AN0":
            continue
        by = {}
        for v in report["cases"].values():
            if v["model"] == model and v["seed"] is not None:
                by.setdefault(v["interface"], []).append(v)
        if not all(i in by for i in INTERFACES):
            continue
        result[model] = {}
        for measure in ("peak_load_N", "pre_yield_load_N"):
            values = {i: {v["seed"]: v[measure] for v in by[i] if v[measure] is not None}
                      for i in INTERFACES}
            result[model][measure] = {
                f"{a} vs {b}": ens.paired_difference(values[a], values[b])
                for a, b in (("EL", "NL-A"), ("NL-A", "NL-B"))}
    report["orderings"] = result


def mean_of(report, model, key):
    """{interface: mean of key over the case's packings} for one beam (AN0's case as 'none')."""
    got = {}
    for e in report["ensembles"].values():
        if e["model"] == model and e.get(key):
            got[e["interface"]] = e[key]["mean"]
    return got


def cell(e, scale=1e3, digits=1):
    """'mean ± sd' of a describe() result in kN (or mm with scale 1e-3), '–' when missing."""
    if not e:
        return "–"
    m = f"{e['mean'] / scale:.{digits}f}"
    return m if e["sd"] is None else f"{m} ± {e['sd'] / scale:.{digits}f}"


def figure10(study, model, data, report):
    """One beam's curves, per interface: the band (min-max over packings) and the mean curve, or
    the single curve of a case run on one packing."""
    mine = {e_case: e for e_case, e in report["ensembles"].items() if e["model"] == model}
    if not mine:
        return
    fig, ax = plt.subplots(figsize=(6, 4.2))
    for case, e in sorted(mine.items()):
        itf = e["interface"]
        colour = COLOURS.get(itf, "grey")
        label = itf if itf != "none" else case
        curves = [data[k] for k in e["directories"]]
        if len(curves) == 1:
            ax.plot(curves[0][0] * 1e3, curves[0][1] / 1e3, color=colour, label=label)
            continue
        g, mean, lo, hi = ens.band(curves)
        ax.fill_between(g * 1e3, lo / 1e3, hi / 1e3, color=colour, alpha=0.25, lw=0)
        ax.plot(g * 1e3, mean / 1e3, color=colour,
                label=f"{label}: mean of {len(curves)} packings, band min–max")
    ax.axhline(TABLE3[model][2], color="red", ls="--", lw=1, label=f"experiment peak {TABLE3[model][2]} kN")
    ax.set_xlabel("midspan deflection [mm]")
    ax.set_ylabel("load [kN]")
    ax.set_title(f"{model} ({TABLE3[model][0]}): load-deflection (paper Fig. 10)")
    ax.set_xlim(left=0)
    ax.set_ylim(bottom=0)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(study, f"figure10_{model}.png"), dpi=130)
    plt.close(fig)


def figure10f(study, data, report):
    """Every beam's NL-B curve (AN0's own), the mean over packings where there are several."""
    fig, ax = plt.subplots(figsize=(6, 4.2))
    for case, e in sorted(report["ensembles"].items()):
        if e["interface"] not in ("NL-B", "none"):
            continue
        curves = [data[k] for k in e["directories"]]
        g, mean = (curves[0][0], curves[0][1]) if len(curves) == 1 else ens.band(curves)[:2]
        n = f", mean of {len(curves)}" if len(curves) > 1 else ""
        ax.plot(g * 1e3, mean / 1e3, label=f"{e['model']} ({TABLE3.get(e['model'], ('?',))[0]}{n})")
    ax.set_xlabel("midspan deflection [mm]")
    ax.set_ylabel("load [kN]")
    ax.set_title("NL-B interface, all beams (paper Fig. 10 f)")
    ax.set_xlim(left=0)
    ax.set_ylim(bottom=0)
    ax.legend()
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(study, "figure10f_NL-B.png"), dpi=130)
    plt.close(fig)


def figure_crack_height(study, data, paths):
    fig, ax = plt.subplots(figsize=(6, 4.2))
    for k in sorted(data):
        cd, cz = crack_growth(paths[k])
        if cd:
            ax.step(np.array(cd) * 1e3, np.array(cz) * 1e3, where="post", label=k)
    ax.axhline(H * 1e3, color="grey", lw=0.8)
    ax.set_xlabel("midspan deflection [mm]")
    ax.set_ylabel("highest broken point within 100 mm of midspan [mm]")
    ax.set_title("Crack growth toward the loading plate")
    ax.legend(fontsize=7, ncol=2)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(study, "crack_height.png"), dpi=130)
    plt.close(fig)


def table3_lines(report, commit):
    """Table 3 beside the paper's (means ± sd over packings), and the supports' peaks."""
    lines = ["# Three-point bending: peak loads beside the paper's Table 3", "",
             f"rcdem {commit}. Peak loads in kN. Paper: P_exp (experiment) and the paper's EL, NL-A, "
             "NL-B; rcdem: this study, mean ± sample standard deviation over the packings a case "
             "ran on (one value where it ran on one). Error: rcdem NL-B's mean against the "
             "experiment. EL ≥ NL-A ≥ NL-B compares the means; the ordering section below tests it.",
             "",
             "| model | bars | f_y (MPa) | P exp | paper EL | paper NL-A | paper NL-B | rcdem EL "
             "| rcdem NL-A | rcdem NL-B | NL-B error | EL ≥ NL-A ≥ NL-B |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for model, (bars, fy, pexp, pel, pna, pnb) in TABLE3.items():
        got = mean_of(report, model, "peak_load_N")
        if not got:
            continue
        mine, err, order = by_interface(model, got, pexp)
        cells = {e["interface"]: e["peak_load_N"] for e in report["ensembles"].values()
                 if e["model"] == model}
        if model == "AN0":
            cells = {"EL": cells.get("none")}
        report["models"][model] = {"experiment_N": pexp * 1e3, "rcdem_N": mine, "nl_b_error": err,
                                   "ordering_holds": order}
        lines.append(
            f"| {model} | {bars} | {fy or '–'} | {pexp} | {pel or '–'} | {pna or '–'} | {pnb or '–'} "
            f"| {cell(cells.get('EL'))} | {cell(cells.get('NL-A'))} | {cell(cells.get('NL-B'))} "
            f"| {'–' if err is None else f'{100 * err:+.1f}%'} "
            f"| {'–' if order is None else ('yes' if order else 'NO')} |")
    lines += ["", "AN0 has no bars: its single case is listed under EL (the paper's AN0 value is "
              "under EL too) and its error is against the experiment.", "",
              "## Peaks of the support reactions", "",
              "The same peaks (means over packings) read from the sum of the two supports' "
              "reactions (the load the beam carries; sampled at the history rows) instead of the "
              "loading plate's force: a peak of the plate's force that the reactions do not reach "
              "is a local, dynamic event under the plate, not the beam's strength.", "",
              "| model | P exp | rcdem EL | rcdem NL-A | rcdem NL-B | NL-B error | EL ≥ NL-A ≥ NL-B |",
              "|---|---|---|---|---|---|---|"]
    for model, (bars, fy, pexp, pel, pna, pnb) in TABLE3.items():
        got = mean_of(report, model, "reaction_peak_N")
        if not got:
            continue
        mine, err, order = by_interface(model, got, pexp)
        report["models"][model]["reactions_N"] = mine
        report["models"][model]["reactions_nl_b_error"] = err
        report["models"][model]["reactions_ordering_holds"] = order
        lines.append(
            f"| {model} | {pexp} | {fmt_kn(mine.get('EL'))} | {fmt_kn(mine.get('NL-A'))} "
            f"| {fmt_kn(mine.get('NL-B'))} | {'–' if err is None else f'{100 * err:+.1f}%'} "
            f"| {'–' if order is None else ('yes' if order else 'NO')} |")
    return lines + imbalance_lines(report)


# SPEC 6's quasi-static test applies to the plate's force and to the supports' reactions: where
# their peaks differ by more than this the study says so.
PLATE_SUPPORT_TOLERANCE = 0.02


def imbalance_lines(report):
    """The runs whose plate peak and supports' peak differ by more than PLATE_SUPPORT_TOLERANCE
    (recorded in report["plate_support_imbalance"])."""
    off = {k: c["peak_load_N"] / c["reaction_peak_N"] - 1 for k, c in sorted(report["cases"].items())
           if c.get("reaction_peak_N")}
    report["plate_support_imbalance"] = off
    bad = {k: v for k, v in off.items() if abs(v) > PLATE_SUPPORT_TOLERANCE}
    worst = max(off.items(), key=lambda kv: abs(kv[1]), default=None)
    lines = [""]
    if not bad:
        lines.append(f"Every run's plate peak is within {100 * PLATE_SUPPORT_TOLERANCE:.0f}% of its "
                     "supports' peak" + (f" (largest: {worst[0]}, {100 * worst[1]:+.1f}%)." if worst else "."))
    else:
        lines.append(f"**Plate and supports differ by more than {100 * PLATE_SUPPORT_TOLERANCE:.0f}% "
                     "at the peak** (not quasi-static there; plate peak ÷ supports' peak − 1): "
                     + ", ".join(f"{k} {100 * v:+.1f}%" for k, v in bad.items()) + ".")
    return lines


def ensemble_lines(report):
    """Per case over its packings, and the orderings with their tests."""
    lines = ["", "## Each case over its packings", "",
             "Mean ± sample standard deviation [min – max] over the packings (generation.seed) "
             "the case ran on. Pre-yield load: the load at one deflection per beam, "
             f"{ens.PRE_YIELD_FRACTION:g} × the smallest deflection at which any of its runs first "
             "yields a bar (or ends, if none does), averaged over the last "
             f"{100 * ens.PRE_YIELD_WINDOW:g}% of that deflection: the cracked concrete and the "
             "bond before the steel yields (tension stiffening).", "",
             "| case | packings | peak (kN) | δ at peak (mm) | pre-yield load (kN) at δ (mm) "
             "| steps (mean) | wall (s, mean) | energy balance (largest) |",
             "|---|---|---|---|---|---|---|---|"]
    for case, e in sorted(report["ensembles"].items()):
        rng = (lambda x, s: "" if not x or x["n"] < 2 else f" [{x['min'] / s:.1f} – {x['max'] / s:.1f}]")
        at = e["pre_yield_deflection_m"]
        eb = e["energy_balance_error"]
        lines.append(
            f"| {case} | {', '.join(str(s) for s in e['seeds'])} "
            f"| {cell(e['peak_load_N'])}{rng(e['peak_load_N'], 1e3)} "
            f"| {cell(e['deflection_at_peak_m'], 1e-3, 3)} "
            f"| {cell(e['pre_yield_load_N'])}{rng(e['pre_yield_load_N'], 1e3)}"
            f"{'' if at is None else f' at {at * 1e3:.3f}'} "
            f"| {e['steps']['mean']:.0f} | {e['wall_time_s']['mean']:.0f} "
            f"| {'–' if not eb else '{:.3f}%'.format(100 * eb['max'])} |")
    lines += ["", "## EL ≥ NL-A ≥ NL-B, tested", "",
              "Each pair of interfaces of a beam on the packings both ran on (the same seed gives the "
              "same packing for every interface): the mean difference, its 95% confidence interval "
              "(t, two-sided) and the one-sided paired t-test's p-value that the first carries "
              f"more; 'first > second' where p < {ens.SIGNIFICANCE:g}, 'second > first' where the "
              "opposite one-sided test gives that, otherwise not distinguishable at that level.", "",
              "| model | measure | pair | packings | means (kN) | difference (kN) | 95% CI (kN) "
              "| p (first > second) | verdict |",
              "|---|---|---|---|---|---|---|---|---|"]
    names = {"peak_load_N": "peak", "pre_yield_load_N": "pre-yield load"}
    for model, measures in report["orderings"].items():
        for measure, pairs in measures.items():
            for pair, t in pairs.items():
                if t is None:
                    lines.append(f"| {model} | {names[measure]} | {pair} | < 2 | – | – | – | – | "
                                 "no test (one packing) |")
                    continue
                lines.append(
                    f"| {model} | {names[measure]} | {pair} | {t['n']} | {t['mean_first'] / 1e3:.2f} / "
                    f"{t['mean_second'] / 1e3:.2f} | {t['mean_difference'] / 1e3:+.2f} | "
                    f"[{t['ci95'][0] / 1e3:+.2f}, {t['ci95'][1] / 1e3:+.2f}] | {t['p_first_greater']:.3f} "
                    f"| {t['verdict']} |")
    if not report["orderings"]:
        lines.append("(no beam ran all three interfaces on common packings)")
    return lines


def behaviour_lines(report):
    lines = ["",
             "## Behaviour per run", "",
             f"Cracking load: the largest load before the load first falls {100 * DROP:g}% below it. "
             "Ductile: past twice the cracking deflection the load rises above the cracking load again, "
             "or it never drops that much (no drop); brittle: it does not. "
             "Initial stiffness K0: least-squares slope between 10% and 40% of the load at which the first "
             "local point broke, over the history rows where the kinetic energy is below "
             f"{100 * K0_KINETIC_LIMIT:g}% of the strain energy; † where fewer than 3 rows qualify (at the "
             "study's rates the beam's steady motion keeps the kinetic energy above that until near "
             "cracking): read over all the window's rows, with their kinetic/strain range and largest "
             "imbalance between the loading plate and the supports; "
             "Timoshenko: simply supported, central load, uncracked transformed section, "
             f"E = {E_CONCRETE / 1e9:.2f} GPa, ν = {NU_CONCRETE}, κ = 5/6.", "",
             "| run | cracking load (kN) | peak (kN) | δ at peak (mm) | reactions' peak (kN) at δ (mm) "
             "| class | K0 (kN/mm) | "
             "Timoshenko, span 600 / 580 mm (kN/mm) | first broken points: x − midspan, z (mm) | crack height at "
             "peak / end (mm) | stop | steps | wall (s) |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for c, v in sorted(report["cases"].items()):
        fc = v["first_cracking"]
        where = ("–" if not fc else
                 f"{(fc['centroid_m'][0] - LENGTH / 2) * 1e3:+.0f}, {max(0.0, fc['centroid_m'][2]) * 1e3:.0f}")
        hp, hf = v["crack_height_at_peak_m"], v["crack_height_final_m"]
        lines.append(
            f"| {c} | {fmt_kn(v['cracking_load_N'])} | {fmt_kn(v['peak_load_N'])} | "
            f"{v['deflection_at_peak_m'] * 1e3:.3f} | "
            f"{fmt_kn(v.get('reaction_peak_N'))} at {1e3 * v.get('deflection_at_reaction_peak_m', float('nan')):.3f} | "
            f"{v['class']} | "
            f"{k0_cell(v)} | {v['timoshenko_stiffness_N_per_m'] / 1e6:.1f} / {v['timoshenko_stiffness_inner_span_N_per_m'] / 1e6:.1f} | "
            f"{where} | {'–' if hp is None else f'{hp * 1e3:.0f}'} / {'–' if hf is None else f'{hf * 1e3:.0f}'} | "
            f"{v['stop_reason']} | {v['steps']} | {v['wall_time_s']:.0f} |")
    return lines


def transition_lines(report):
    """The first beam, in order of steel, whose NL-B runs are mostly ductile after a beam whose
    runs are mostly brittle (AN0: its own case)."""
    classes, counts = [], {}
    for model in TABLE3:
        runs = [v for v in report["cases"].values()
                if v["model"] == model and v["interface"] in ("NL-B", "none")]
        if not runs:
            continue
        ductile = sum(v["class"].startswith("ductile") for v in runs)
        counts[model] = (ductile, len(runs))
        classes.append((model, "ductile" if 2 * ductile > len(runs) else "brittle"))
    transition = next((m for (m, k), (_, kp) in zip(classes[1:], classes[:-1])
                       if k == "ductile" and kp == "brittle"), None)
    report["classes_nl_b"] = dict(classes)
    report["transition_at"] = transition
    return ["", "## Brittle-to-ductile transition", "",
            "NL-B (AN0: no bars), ductile runs of all: "
            + ", ".join(f"{m} {k} ({counts[m][0]}/{counts[m][1]})" for m, k in classes) + ".",
            f"Transition (first mostly ductile beam after a mostly brittle one): {transition or 'not seen'}"
            f"{' (' + TABLE3[transition][0] + ')' if transition else ''}; paper: at 2Φ5 (AN2)."
            ] + transition_by_packing(report)


def transition_by_packing(report):
    """Per packing, the NL-B runs (AN0: its own case) in order of steel and the first ductile
    beam; the transition is at that beam on this packing when every beam with less steel ran
    on it and is brittle (the beams with more steel that are brittle are named)."""
    seeds = sorted({v["seed"] for v in report["cases"].values() if v["seed"] is not None})
    report["transition_by_seed"] = {}
    lines = []
    for seed in seeds:
        cls = {v["model"]: v["class"].startswith("ductile") for v in report["cases"].values()
               if v["seed"] == seed and v["interface"] in ("NL-B", "none")}
        order = [m for m in TABLE3 if m in cls]
        first = next((m for m in order if cls[m]), None)
        below = MODELS[:MODELS.index(first)] if first else []
        at = first if first and all(m in cls and not cls[m] for m in below) else None
        report["transition_by_seed"][str(seed)] = at
        after = [m for m in order[order.index(first) + 1:] if not cls[m]] if first else []
        missing = [m for m in below if m not in cls]
        what = (f"at {at}" if at else f"not established ({', '.join(missing)} not run)" if missing
                else "not seen")
        lines.append(f"- packing {seed}: " + ", ".join(
            f"{m} {'ductile' if cls[m] else 'brittle'}" for m in order) + f" → transition {what}"
            + (f"; brittle above it: {', '.join(after)}" if after else "") + ".")
    if not lines:
        return []
    return ["", "Per packing (criterion: the first beam, in order of steel, whose NL-B run is "
            "ductile, every beam with less steel run on that packing and brittle):", ""] + lines


def commit_of(runs):
    """The rcdem commit(s) that ran the study's runs, from their manifests."""
    found = set()
    for r in runs:
        try:
            m = json.load(open(os.path.join(r["path"], "manifest.json")))
        except (OSError, ValueError):
            continue
        for s in m.get("sessions", [m]):
            if s.get("git_hash"):
                found.add(s["git_hash"])
    return "commit " + ", ".join(sorted(found)) if found else "commit not recorded"


def is_paper_run(r):
    """A run of one of the paper's beams as the paper ran it: a case named after a model of Table 3
    (AN0, AN2_NL-B, ...) on the paper's three-point set-up, with no swept key."""
    try:
        s = json.load(open(os.path.join(r["path"], "summary.json")))
    except (OSError, ValueError):
        return False
    return (r.get("model") in TABLE3 and not r.get("variant") and s.get("control") == "load"
            and s.get("displacement_column", "load_displacement_m") == "load_displacement_m")


def generic_report(runs, out):
    """Any study's cases as they are: each run named by its directory (case, swept value, seed)
    in every table and legend; its load-displacement curve, peak and how it ended."""
    data, report = {}, {"cases": {}, "kind": "generic"}
    for r in runs:
        k = r["directory"]
        d, p = curve(r["path"])
        data[k] = (d, p)
        with open(os.path.join(out, "curves", k + ".csv"), "w") as f:
            f.write("displacement_m,load_N\n")
            f.writelines(f"{a:.8g},{b:.8g}\n" for a, b in zip(d, p))
        s = json.load(open(os.path.join(r["path"], "summary.json")))
        report["cases"][k] = {
            "case": r["case"], "variant": r.get("variant") or "", "seed": r["seed"],
            "control": s.get("control"), "displacement_column": s.get("displacement_column"),
            "peak_load_N": s["peak_load_N"], "displacement_at_peak_m": s["displacement_at_peak_m"],
            "stop_reason": s.get("stop_reason"), "steps": s.get("steps"),
            "energy_balance_error": s["energy"]["balance_error"]}
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for k in sorted(data):
        d, p = data[k]
        ax.plot(1e3 * d, 1e-3 * p, lw=1.2, label=k)
    ax.set_xlabel("displacement (mm)")
    ax.set_ylabel("load (kN)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "load_displacement.png"), dpi=110)
    plt.close(fig)
    report["commit"] = commit_of(runs)
    lines = [f"# Study: {len(runs)} runs ({report['commit']})", "",
             "| run | case | swept value | seed | peak (kN) | displacement at peak (mm) | stopped by "
             "| steps | energy balance |", "|---|---|---|---|---|---|---|---|---|"]
    for k in sorted(report["cases"]):
        c = report["cases"][k]
        lines.append(
            f"| {k} | {c['case']} | {c['variant'] or '-'} | {c['seed']} | "
            f"{c['peak_load_N'] / 1e3:.2f} | {abs(c['displacement_at_peak_m']) * 1e3:.4f} | "
            f"{c['stop_reason']} | {c['steps']} | {c['energy_balance_error']:.2g} |")
    with open(os.path.join(out, "cases.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    with open(os.path.join(out, "report.json"), "w") as f:
        json.dump(report, f, indent=2)
    print("\n".join(lines))


def main(studies, out):
    runs = read_studies(studies)
    if not runs:
        sys.exit(f"{', '.join(studies)}: no finished case")
    os.makedirs(os.path.join(out, "curves"), exist_ok=True)
    if [os.path.abspath(out)] != [os.path.abspath(s) for s in studies]:
        write_merged_tables(out, studies)
    if not all(is_paper_run(r) for r in runs):
        generic_report(runs, out)
        return
    data, report = {}, {"cases": {}, "models": {}}  # data: run directory -> (deflection, load)
    paths = {r["directory"]: r["path"] for r in runs}
    for r in runs:
        k = r["directory"]
        rows = history(r["path"])
        d, p = curve(r["path"], rows)
        data[k] = (d, p)
        with open(os.path.join(out, "curves", k + ".csv"), "w") as f:
            f.write("deflection_m,load_N\n")
            f.writelines(f"{a:.8g},{b:.8g}\n" for a, b in zip(d, p))
        report["cases"][k] = run_report(r, r["path"], rows, d, p)
    ensembles(report, data)
    orderings(report)
    for model in TABLE3:
        figure10(out, model, data, report)
    figure10f(out, data, report)
    figure_crack_height(out, data, paths)
    for k in sorted(data):
        figure9(k, paths[k], out)
        figure8(k, paths[k], out)
    commit = commit_of(runs)
    report["commit"] = commit
    lines = (table3_lines(report, commit) + ensemble_lines(report) + behaviour_lines(report)
             + transition_lines(report))
    with open(os.path.join(out, "table3.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    with open(os.path.join(out, "report.json"), "w") as f:
        json.dump(report, f, indent=2)
    print("\n".join(lines))


def parse_args(argv):
    """(studies, out) from `STUDY_DIR` or `-o OUT_DIR STUDY_DIR...`."""
    if len(argv) == 1 and not argv[0].startswith("-"):
        return argv, argv[0]
    if len(argv) >= 3 and argv[0] == "-o" and not any(a.startswith("-") for a in argv[2:]):
        return argv[2:], argv[1]
    sys.exit(__doc__)


if __name__ == "__main__":
    main(*parse_args(sys.argv[1:]))
