#!/usr/bin/python3
"""Resources and signals (issue 44, class 5):

  * a file-size limit (ulimit -f, with SIGXFSZ at its default as a shell leaves it): the run ends
    with an `rcdem: error:` naming the failed write, not killed by SIGXFSZ;
  * far more snapshots than steps: a warning at the set-up with the outputs' volume, within a
    factor 1.5 of what is then written;
  * SIGHUP (a closed terminal): the run checkpoints and exits 129, and resumes to the end;
  * a study killed by SIGKILL: its running case stops within 10 s, with a checkpoint;
  * option errors: one line with `rcdem: error:` and exit 2; a mistyped command is named; -q
    after the command works.

usage: check_signals_resources.py RCDEM_BINARY SOURCE_DIR
"""
import glob
import json
import os
import resource
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
SCENARIO = open(os.path.join(source, "tests/regression/small_run.toml")).read()


def alive(pid):
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().split()[2] != "Z"
    except OSError:
        return False


with tempfile.TemporaryDirectory() as tmp:
    scenario = os.path.join(tmp, "s.toml")
    open(scenario, "w").write(SCENARIO)

    def limited():
        signal.signal(signal.SIGXFSZ, signal.SIG_DFL)  # Python ignores it; a shell does not
        resource.setrlimit(resource.RLIMIT_FSIZE, (200_000, 200_000))

    r = subprocess.run([rcdem, "-q", "run", scenario, "-o", os.path.join(tmp, "fsize")],
                       capture_output=True, text=True, timeout=300, preexec_fn=limited)
    check(r.returncode == 1 and "rcdem: error:" in r.stderr and "File too large" in r.stderr,
          f"under ulimit -f: a write error, not SIGXFSZ (returncode {r.returncode}: "
          f"{r.stderr.strip()[-200:]})")

    many = os.path.join(tmp, "many.toml")
    open(many, "w").write(SCENARIO.replace("steps = 3000", "steps = 300")
                          .replace("snapshots = 3", "snapshots = 100000"))
    out = os.path.join(tmp, "many")
    r = subprocess.run([rcdem, "run", many, "-o", out], capture_output=True, text=True, timeout=300)
    warned = [x for x in r.stderr.splitlines() if "the snapshots will take about" in x]
    size = sum(os.path.getsize(f) for f in glob.glob(os.path.join(out, "snapshots", "*")))
    est = float(warned[0].split("about ")[1].split(" GB")[0]) * 1e9 if warned else 0.0
    check(r.returncode == 0 and warned and size / 1.5 < est < size * 1.5,
          f"100,000 snapshots of a 300-step run: a warning at the set-up ({est / 1e6:.1f} MB "
          f"estimated, {size / 1e6:.1f} MB written)")

    out = os.path.join(tmp, "hup")
    p = subprocess.Popen([rcdem, "-q", "run", scenario, "-o", out], stdout=subprocess.DEVNULL,
                         stderr=subprocess.PIPE, text=True)
    t0 = time.time()
    while time.time() - t0 < 120 and not os.path.exists(os.path.join(out, "history.csv")):
        time.sleep(0.01)
    time.sleep(0.3)
    p.send_signal(signal.SIGHUP)
    _, err = p.communicate(timeout=120)
    ck = glob.glob(os.path.join(out, "checkpoint_*.h5"))
    check(p.returncode == 129 and ck, f"SIGHUP: exit {p.returncode}, {len(ck)} checkpoint(s) "
          f"({err.strip()[-120:]})")
    r = subprocess.run([rcdem, "-q", "run", "--resume", out], capture_output=True, text=True,
                       timeout=300)
    check(r.returncode == 0 and os.path.exists(os.path.join(out, "summary.json")),
          "the run stopped by SIGHUP resumes to its end")

    # A study killed by SIGKILL.
    scen_dir = os.path.join(tmp, "study_scenarios")
    os.makedirs(scen_dir)
    open(os.path.join(scen_dir, "long.toml"), "w").write(SCENARIO.replace("steps = 3000",
                                                                          "steps = 200000"))
    sdir = os.path.join(tmp, "study")
    p = subprocess.Popen([rcdem, "-q", "study", "generic", "--scenarios", scen_dir, "-o", sdir],
                         stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    case = os.path.join(sdir, "cases", "long")
    t0 = time.time()
    while time.time() - t0 < 120 and not os.path.exists(os.path.join(case,
                                                                      "particles_initial.vtu")):
        time.sleep(0.02)
    time.sleep(1.0)
    kids = open(f"/proc/{p.pid}/task/{p.pid}/children").read().split()
    p.kill()
    p.wait()
    t0 = time.time()
    while time.time() - t0 < 10 and any(alive(k) for k in kids):
        time.sleep(0.05)
    check(kids and not any(alive(k) for k in kids),
          f"a SIGKILLed study's running case stops ({len(kids)} child, "
          f"{time.time() - t0:.1f} s)")
    m = json.load(open(os.path.join(case, "manifest.json")))
    check(glob.glob(os.path.join(case, "checkpoint_*.h5")) and m["exit_state"] == "interrupted",
          f"and it checkpointed (manifest: {m['exit_state']})")

    for args, what in ((["run", "--bogus"], "an unknown option"),
                       (["run", "--checkpoint-every"], "an option without its value"),
                       (["study"], "a missing argument"),
                       (["runn", scenario], "a mistyped command")):
        r = subprocess.run([rcdem] + args, capture_output=True, text=True, timeout=60)
        lines = r.stderr.strip().splitlines()
        check(r.returncode == 2 and len(lines) == 1 and lines[0].startswith("rcdem: error:")
              and ("'runn'" in lines[0] if what == "a mistyped command" else True),
              f"{what}: exit {r.returncode}, one line: {lines[:1]}")
    r = subprocess.run([rcdem, "run", scenario, "-o", os.path.join(tmp, "q"), "-q"],
                       capture_output=True, text=True, timeout=300)
    check(r.returncode == 0 and r.stderr == "" and r.stdout == "", "-q after the command is quiet")

checks.finish()
