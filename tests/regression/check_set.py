#!/usr/bin/python3
"""`--set KEY=VALUE` (issue 45, item 2) on tests/regression/small_run.toml:

  * `run --set` gives history.csv byte for byte as the run of the file edited by hand, and the
    run's scenario.toml and manifest.json record the values;
  * a run started with --set and interrupted resumes (from its own scenario.toml) to the same
    history as the uninterrupted one;
  * a bad key, a bad value, a key given twice: one `rcdem: error:` line naming the --set item,
    exit 1, nothing written;
  * `study --set` applies the value to every case (their manifests record it).

usage: check_set.py RCDEM_BINARY SOURCE_DIR
"""
import json
import os
import signal
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checklist import Checklist  # noqa: E402

rcdem, source = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
checks = Checklist()
check = checks.check
TEXT = open(os.path.join(source, "tests/regression/small_run.toml")).read()
PRESET = 'preset = "basic"'  # small_run.toml's [solver] line
SETS = ["stop.steps=1500", "plates.top.velocity=-0.3", "solver.damping=0.2"]


def run(args):
    return subprocess.run([rcdem, "-q"] + args, capture_output=True, text=True, timeout=300)


def history(d):
    return open(os.path.join(d, "history.csv"), "rb").read()


with tempfile.TemporaryDirectory() as tmp:
    base = os.path.join(tmp, "base.toml")
    open(base, "w").write(TEXT)
    edited = os.path.join(tmp, "edited.toml")
    open(edited, "w").write(TEXT.replace("steps = 3000", "steps = 1500")
                            .replace("velocity = -0.5", "velocity = -0.3")
                            .replace(PRESET, PRESET + "\ndamping = 0.2"))
    args = [a for s in SETS for a in ("--set", s)]
    r1 = run(["run", base, "-o", os.path.join(tmp, "set")] + args)
    r2 = run(["run", edited, "-o", os.path.join(tmp, "edited")])
    check(r1.returncode == 0 and r2.returncode == 0
          and history(os.path.join(tmp, "set")) == history(os.path.join(tmp, "edited")),
          "run --set gives the edited file's history.csv, byte for byte")
    copy = open(os.path.join(tmp, "set", "scenario.toml")).read()
    m = json.load(open(os.path.join(tmp, "set", "manifest.json")))
    check("steps = 1500" in copy and "velocity = -0.3" in copy and "damping = 0.2" in copy
          and m["set"] == SETS, f"scenario.toml and manifest.json record the values ({m['set']})")

    d = os.path.join(tmp, "interrupted")
    p = subprocess.Popen([rcdem, "-q", "run", base, "-o", d, "--checkpoint-every", "200"] + args,
                         stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    while p.poll() is None and not (os.path.isdir(d) and any(f.startswith("checkpoint_")
                                                             for f in os.listdir(d))):
        time.sleep(0.01)
    p.send_signal(signal.SIGINT)
    p.wait()
    r = run(["run", "--resume", d])
    check(p.returncode == 130 and r.returncode == 0
          and history(d) == history(os.path.join(tmp, "set")),
          "a --set run interrupted and resumed ends as the uninterrupted one")

    for item, expect in (("solver.dampin=0.3", "unknown key 'solver.dampin'"),
                         ("solver.damping=abc", "expected a number in [0, 1), got \"abc\""),
                         ("plates.top.velocity=[1, 2]", "plates.top.velocity"),
                         ("stop.steps", "expected KEY=VALUE")):
        out = os.path.join(tmp, "bad")
        r = run(["run", base, "-o", out, "--set", item])
        lines = r.stderr.strip().splitlines()
        check(r.returncode == 1 and len(lines) == 1
              and lines[0].startswith(f"rcdem: error: --set '{item}'") and expect in lines[0]
              and not os.path.exists(out),
              f"--set {item!r}: one line naming it, exit {r.returncode} ({lines[:1]})")
    r = run(["run", base, "-o", os.path.join(tmp, "bad"), "--set", "stop.steps=1",
             "--set", "stop.steps=2"])
    check(r.returncode == 1 and "stop.steps is given twice" in r.stderr, "a key given twice")

    scen = os.path.join(tmp, "cases")
    os.makedirs(scen)
    for name in ("a", "b"):
        open(os.path.join(scen, name + ".toml"), "w").write(TEXT)
    sd = os.path.join(tmp, "study")
    r = run(["study", "generic", "--scenarios", scen, "-o", sd, "--set", "stop.steps=300"])
    ms = [json.load(open(os.path.join(sd, "cases", n, "manifest.json"))) for n in ("a", "b")]
    ss = [json.load(open(os.path.join(sd, "cases", n, "summary.json"))) for n in ("a", "b")]
    check(r.returncode == 0 and all(m["set"] == ["stop.steps=300"] for m in ms)
          and all(s["steps"] == 300 for s in ss), "study --set applies to every case")

checks.finish()
