#!/usr/bin/python3
"""A generic study with a sweep (issue 41, item 5): examples/four_point_bending/plain.toml (not
one of the paper's beams) swept over three values of contact.sigma_nt with
`rcdem study --scenarios DIR --sweep contact.sigma_nt=3e6,3.5e6,4.23e6`:

  * three runs, each named <case>_sigma_nt=<value>, each row of cases.csv, peak_loads.csv,
    cases.md and report.json distinct and naming its value, three curves (the figure's legend is
    their names), and each run's manifest records its value;
  * the study writes its tables and figure (cases.md, load_displacement.png), not the paper's;
  * a sweep without values, with a key also given to --set, or with a value the schema refuses:
    one error line, exit 1, nothing run.

usage: check_sweep.py RCDEM_BINARY SOURCE_DIR
"""
import csv
import json
import os
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checklist import Checklist  # noqa: E402

rcdem, source = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
checks = Checklist()
check = checks.check
VALUES = ["3e6", "3.5e6", "4.23e6"]

with tempfile.TemporaryDirectory() as tmp:
    scenarios = os.path.join(tmp, "scenarios")
    os.makedirs(scenarios)
    text = open(os.path.join(source, "examples/four_point_bending/plain.toml")).read()
    text = text.replace('include = ["../calibrated_contact.toml"]',
                        f'include = ["{source}/examples/calibrated_contact.toml"]')
    open(os.path.join(scenarios, "plain.toml"), "w").write(text)
    out = os.path.join(tmp, "study")
    r = subprocess.run([rcdem, "-q", "study", "four_point", "--scenarios", scenarios, "-o", out,
                        "--sweep", "contact.sigma_nt=" + ",".join(VALUES), "-j", "2",
                        "--set", "output.snapshots=0"],
                       capture_output=True, text=True, timeout=900)
    check(r.returncode == 0, f"the swept study runs (exit {r.returncode}: {r.stderr[-300:]})")
    names = [f"plain_sigma_nt={v}" for v in VALUES]
    cases = list(csv.DictReader(open(os.path.join(out, "cases.csv"))))
    check(sorted(c["directory"] for c in cases) == sorted(names) and
          all(c["status"] == "finished" for c in cases),
          f"cases.csv: three finished runs named by their value ({[c['directory'] for c in cases]})")
    peaks = list(csv.DictReader(open(os.path.join(out, "peak_loads.csv"))))
    check(sorted(p["directory"] for p in peaks) == sorted(names) and
          sorted(p["variant"] for p in peaks) == sorted(f"contact.sigma_nt={v}" for v in VALUES),
          "peak_loads.csv: three rows, each with its run and value")
    report = json.load(open(os.path.join(out, "report.json")))
    check(report.get("kind") == "generic" and sorted(report["cases"]) == sorted(names),
          f"report.json: the generic report, one entry per run ({sorted(report['cases'])})")
    table = open(os.path.join(out, "cases.md")).read() if os.path.exists(
        os.path.join(out, "cases.md")) else ""
    check(all(table.count(f"| {n} |") == 1 for n in names), "cases.md: one row per run")
    check(sorted(os.listdir(os.path.join(out, "curves"))) == sorted(n + ".csv" for n in names),
          "one curve per run (the figure's legend entries)")
    check(os.path.exists(os.path.join(out, "load_displacement.png")) and
          not os.path.exists(os.path.join(out, "table3.md")),
          "the study's own figure, not the paper's table")
    for n, v in zip(names, VALUES):
        m = json.load(open(os.path.join(out, "cases", n, "manifest.json")))
        check(f"contact.sigma_nt={v}" in json.dumps(m.get("set", m)),
              f"{n}: its manifest records contact.sigma_nt={v}")
    peaks_by = {p["directory"]: float(p["peak_load_N"]) for p in peaks}
    check(len(set(peaks_by.values())) == 3, f"three distinct peaks ({peaks_by})")

    for args, what in (
            (["--sweep", "contact.sigma_nt"], "expected KEY=V1,V2"),
            (["--sweep", "contact.sigma_nt=3e6,3e6"], "distinct"),
            (["--sweep", "contact.sigma_nt=3e6,4e6", "--set", "contact.sigma_nt=2e6"],
             "also given to --set"),
            (["--sweep", "contact.sigma_nt=3e6,-1"], "contact.sigma_nt")):
        bad = os.path.join(tmp, "bad")
        shutil.rmtree(bad, ignore_errors=True)
        r = subprocess.run([rcdem, "-q", "study", "four_point", "--scenarios", scenarios, "-o", bad]
                           + args, capture_output=True, text=True, timeout=120)
        lines = r.stderr.strip().splitlines()
        check(r.returncode == 1 and len(lines) == 1 and lines[0].startswith("rcdem: error:") and
              what in lines[0] and not os.path.exists(os.path.join(bad, "cases")),
              f"{' '.join(args)}: one error line ({r.stderr.strip()[:160]})")
checks.finish()
