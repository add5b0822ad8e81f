#!/usr/bin/python3
"""A study trusts nothing it did not check (issue 44, class 3), on the quick AN0 beam run as a
study of a scenario directory:

  * a finished case whose history.csv was cut or deleted, or whose summary.json is `{}`, `[]` or
    has a string for a number, stops the study with exit 1 and a message naming the file (never
    an internal error), and leaves no report (table3.md, report.json, figures) behind;
  * a finished case whose scenario was edited is run again, and the table shows the new run;
  * a report that fails is an error (exit 1, its cause and log named), with no table3.md left.

usage: check_study_trust.py RCDEM_BINARY SOURCE_DIR
"""
import glob
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
REPORT = ("table3.md", "report.json")


def study(scenarios, out, **kw):
    return subprocess.run([rcdem, "study", "three_point_bending", "--scenarios", scenarios,
                           "-o", out], capture_output=True, text=True, timeout=1200, **kw)


def no_report(out):
    return not any(os.path.exists(os.path.join(out, f)) for f in REPORT) and not glob.glob(
        os.path.join(out, "figure*.png"))


with tempfile.TemporaryDirectory() as tmp:
    scenarios = os.path.join(tmp, "scenarios")
    os.makedirs(scenarios)
    text = open(os.path.join(source, "examples/three_point_bending/study/quick/AN0.toml")).read()
    text = text.replace('"../../../calibrated_contact_quick.toml"',
                        json.dumps(os.path.join(source, "examples/calibrated_contact_quick.toml")))
    # Loaded 4x faster than the study's quasi-static rate: what is checked is the study's
    # bookkeeping, and the beam is run a dozen times.
    assert "velocity = -0.0125" in text
    text = text.replace("velocity = -0.0125", "velocity = -0.05")
    scenario = os.path.join(scenarios, "AN0.toml")
    open(scenario, "w").write(text)
    out = os.path.join(tmp, "study")
    r = study(scenarios, out)
    check(r.returncode == 0 and os.path.exists(os.path.join(out, "table3.md")),
          f"the study runs and reports (exit {r.returncode}: {r.stderr.strip()[-300:]})")
    case = os.path.join(out, "cases", "AN0")
    pristine = os.path.join(tmp, "pristine")
    shutil.copytree(case, pristine)

    def tamper(what, edit, name):
        shutil.rmtree(case)
        shutil.copytree(pristine, case)
        edit(os.path.join(case, name))
        r = study(scenarios, out)
        check(r.returncode == 1 and "rcdem: error:" in r.stderr and
              os.path.join(case, name) in r.stderr and no_report(out),
              f"{what}: exit {r.returncode}, the file named, no report left "
              f"({r.stderr.strip().splitlines()[-1][:200] if r.stderr.strip() else ''})")

    def cut(path):
        data = open(path, "rb").read()
        open(path, "wb").write(data[:len(data) // 2])

    def cut_at_line(path):
        lines = open(path).readlines()
        open(path, "w").writelines(lines[:len(lines) // 2])

    tamper("history.csv cut mid-row", cut, "history.csv")
    tamper("history.csv cut at a row's end", cut_at_line, "history.csv")
    tamper("history.csv deleted", os.remove, "history.csv")
    tamper("summary.json is {}", lambda p: open(p, "w").write("{}"), "summary.json")
    tamper("summary.json is []", lambda p: open(p, "w").write("[]"), "summary.json")

    def string_peak(p):
        s = json.load(open(p))
        s["peak_load_N"] = "12 kN"
        json.dump(s, open(p, "w"))
    tamper("summary.json with a string for the peak", string_peak, "summary.json")
    tamper("summary.json cut", cut, "summary.json")

    # The scenario edited: the case runs again.
    shutil.rmtree(case)
    shutil.copytree(pristine, case)
    open(scenario, "w").write(text.replace("seed = 1", "seed = 2"))
    r = study(scenarios, out)
    new = json.load(open(os.path.join(case, "summary.json")))
    old = json.load(open(os.path.join(pristine, "summary.json")))
    check(r.returncode == 0 and "changed since it ran" in r.stderr
          and new["peak_load_N"] != old["peak_load_N"],
          f"an edited scenario's case is run again (exit {r.returncode}; peak "
          f"{old['peak_load_N']:.1f} N then, {new['peak_load_N']:.1f} N now)")

    # The report fails (a matplotlib that cannot be imported).
    fake = os.path.join(tmp, "fake")
    os.makedirs(os.path.join(fake, "matplotlib"))
    open(os.path.join(fake, "matplotlib", "__init__.py"), "w").write(
        "raise ImportError('test: broken')\n")
    r = study(scenarios, out, env=dict(os.environ, PYTHONPATH=fake))
    check(r.returncode == 1 and "the report failed" in r.stderr and "test: broken" in r.stderr
          and no_report(out),
          f"a failed report is an error with its cause, no stale table3.md (exit {r.returncode}: "
          f"{r.stderr.strip().splitlines()[-1][:200] if r.stderr.strip() else ''})")
    r = study(scenarios, out)
    check(r.returncode == 0 and os.path.exists(os.path.join(out, "table3.md")),
          "the same study then reports again without rerunning anything"
          if "not rerun" in r.stderr else f"the study reports again (exit {r.returncode})")

checks.finish()
