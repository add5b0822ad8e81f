#!/usr/bin/python3
"""Bent bars (issue 41, item 4): examples/stirrups/beam.toml, the quick three-point beam with two
longitudinal bars and six closed stirrups tied to them, run to 0.6 mm of deflection.

  * it generates and runs (bent bars: the rounded corners, the closed loops' nodes, the
    interfaces and the selective mass scaling of their short cylinders), energy balance < 0.1%;
  * each stirrup has its history column NAME_max_axial_force_N and a bars.pvd series;
  * each stirrup is tied to the two longitudinal bars its lower bends wrap (12 ties, summary.json's
    bar_ties), and the ties carry force (max_tie_force_N) once cracked: over three times the
    largest before the first broken point;
  * the stirrups carry force once the cracks cross them: at 0.6 mm the two stirrups nearest
    midspan carry over three times the largest stirrup force before the first broken point, and
    over five times what the two nearest the supports carry (the whole run to 1.5 mm:
    docs/model.md 14).

usage: check_stirrups.py RCDEM_BINARY SOURCE_DIR
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
STIRRUPS = ["stirrup_l1", "stirrup_l2", "stirrup_l3", "stirrup_r1", "stirrup_r2", "stirrup_r3"]

with tempfile.TemporaryDirectory() as tmp:
    out = os.path.join(tmp, "run")
    r = subprocess.run([rcdem, "-q", "run", os.path.join(source, "examples/stirrups/beam.toml"),
                        "-o", out, "--set", "stop.displacement=0.0006", "--set",
                        "output.snapshots=2"], capture_output=True, text=True, timeout=900)
    check(r.returncode == 0, f"the beam with stirrups runs (exit {r.returncode}: {r.stderr[-300:]})")
    if r.returncode == 0:
        s = json.load(open(os.path.join(out, "summary.json")))
        check(s["energy"]["balance_error"] < 1e-3,
              f"energy balance {s['energy']['balance_error']:.2g}")
        with open(os.path.join(out, "history.csv")) as f:
            h = [{k: float(v) for k, v in row.items()} for row in csv.DictReader(f)]
        columns = [n + "_max_axial_force_N" for n in STIRRUPS]
        check(all(c in h[0] for c in columns), "a force column per stirrup")
        intact = [x for x in h if x["broken_points"] == 0]
        before = max(max(x[c] for c in columns) for x in intact)
        inner = min(h[-1]["stirrup_l3_max_axial_force_N"], h[-1]["stirrup_r1_max_axial_force_N"])
        outer = max(h[-1]["stirrup_l1_max_axial_force_N"], h[-1]["stirrup_r3_max_axial_force_N"])
        check(inner > 3 * before and inner > 5 * outer,
              f"the stirrups nearest midspan carry {inner:.0f} N once cracked (at most "
              f"{before:.1f} N before the first broken point; {outer:.0f} N near the supports)")
        check(s["specimen"].get("bar_ties") == 12, f"12 ties ({s['specimen'].get('bar_ties')})")
        tie_before = max(x["max_tie_force_N"] for x in intact)
        tie_after = h[-1]["max_tie_force_N"]
        check(tie_after > 3 * tie_before, f"the ties carry {tie_after:.0f} N once cracked (at most "
              f"{tie_before:.1f} N before the first broken point)")
        series = open(os.path.join(out, "bars.pvd")).read()
        check(series.count("<DataSet") >= 2, "bars.pvd holds the bars' snapshots")
checks.finish()
