#!/usr/bin/python3
"""Four-point bending (issue 41, item 3): examples/four_point_bending/plain.toml run whole, with a
history row every step, and reinforced.toml for its first steps.

  * the load is the sum of both loading plates' reactions in every row, and summary.json's peak
    is that load's largest value (it reports the control as both plates);
  * the test's displacement is the midspan gauge (deflection relative to the supports): the
    column summary.json names, its value at the peak summary.json's displacement_at_peak_m; in
    the elastic stage the two plates share the load and the midspan deflects down by more than
    the plates travel, less than beam theory's 23/20 (shear and the plates' indentation);
  * the cracks open in the constant-moment zone: most broken points lie between the loading
    plates, and the bottom fibre's opening gauge there is open at the end;
  * the reinforced beam writes its gauges and bar columns.

usage: check_four_point.py RCDEM_BINARY SOURCE_DIR
"""
import csv
import json
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checklist import Checklist  # noqa: E402

rcdem, source = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
checks = Checklist()
check = checks.check


def run(scenario, out, *sets):
    args = [rcdem, "-q", "run", os.path.join(source, "examples/four_point_bending", scenario),
            "-o", out]
    for s in sets:
        args += ["--set", s]
    return subprocess.run(args, capture_output=True, text=True, timeout=600)


def rows(d):
    with open(os.path.join(d, "history.csv")) as f:
        return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]


with tempfile.TemporaryDirectory() as tmp:
    plain = os.path.join(tmp, "plain")
    r = run("plain.toml", plain, "output.history_rows=1000000", "output.snapshots=0")
    check(r.returncode == 0, f"the plain four-point beam runs (exit {r.returncode}: {r.stderr[-300:]})")
    h = rows(plain)
    summary = json.load(open(os.path.join(plain, "summary.json")))
    check(summary["control"] == "load_left+load_right", f"control: {summary['control']}")
    check(summary["displacement_column"] == "gauge_midspan_m",
          f"displacement column: {summary['displacement_column']}")
    worst = max(abs(x["load_N"] - (x["load_left_force_N"] + x["load_right_force_N"])) /
                max(1.0, abs(x["load_N"])) for x in h)
    check(worst < 1e-9, f"load_N is both loading plates' reactions summed in every row ({worst:.2g})")
    peak = max(h, key=lambda x: x["load_N"])
    check(abs(summary["peak_load_N"] - peak["load_N"]) <= 1e-9 * peak["load_N"],
          f"summary's peak {summary['peak_load_N']:.6g} N is the largest load "
          f"{peak['load_N']:.6g} N")
    check(abs(summary["displacement_at_peak_m"] - peak["gauge_midspan_m"]) <=
          1e-9 * abs(peak["gauge_midspan_m"]),
          f"the displacement at the peak is the midspan gauge's ({peak['gauge_midspan_m']:.4g} m)")
    # The elastic stage: from a fifth to a half of the peak, before the first crack.
    elastic = [x for x in h if 0.2 * peak["load_N"] <= x["load_N"] <= 0.5 * peak["load_N"] and
               x["step"] < peak["step"]]
    split = max(abs(x["load_left_force_N"] - x["load_right_force_N"]) / x["load_N"]
                for x in elastic)
    check(elastic and split < 0.1,
          f"the two plates share the load in the elastic stage (largest difference {split:.1%})")
    ratio = [x["gauge_midspan_m"] / x["control_displacement_m"] for x in elastic]
    check(all(1.0 < q < 23 / 20 for q in ratio),
          f"the midspan deflects down, {min(ratio):.3f}-{max(ratio):.3f} times the loading "
          "plates' travel (beam theory 23/20 at the third points, less with shear and the plates' "
          "indentation)")
    with open(os.path.join(plain, "broken_points.csv")) as f:
        xs = [float(p["x_m"]) for p in csv.DictReader(f)]
    inside = sum(0.25 <= x <= 0.45 for x in xs) / max(1, len(xs))
    check(len(xs) > 100 and inside > 0.75,
          f"the cracks lie in the constant-moment zone ({inside:.0%} of {len(xs)} broken points)")
    check(h[-1]["gauge_bottom_opening_m"] > 1e-5,
          f"the bottom fibre's opening is open at the end ({h[-1]['gauge_bottom_opening_m']:.3g} m)")

    rc = os.path.join(tmp, "reinforced")
    r = run("reinforced.toml", rc, "stop.steps=300", "output.snapshots=0")
    check(r.returncode == 0, f"the reinforced four-point beam runs (exit {r.returncode}: {r.stderr[-300:]})")
    if r.returncode == 0:
        columns = rows(rc)[0].keys()
        check({"gauge_midspan_m", "gauge_bottom_opening_m", "control_displacement_m",
               "max_axial_force_N"} <= set(columns), "the reinforced beam's gauge and bar columns")
checks.finish()
