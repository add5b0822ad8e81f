#!/usr/bin/python3
"""No shell anywhere (issue 44, class 2): rcdem starts its plotting and report tools with an
argument vector, from its own location, and passes a Ctrl-C on.

  * output directories whose names hold a quote, spaces, `$(...)`, a backquote or a newline: the
    run ends normally, its plot is drawn, and nothing named in them is executed;
  * a script named like rcdem's in the working directory's tools/ is not run (rcdem's own is);
  * a Ctrl-C (SIGINT to the process group, as a terminal sends it) while calibrate draws its
    figure ends calibrate by SIGINT, not with exit 0;
  * a failing plot is a warning that names its cause and log; the run still exits 0.

usage: check_no_shell.py RCDEM_BINARY SOURCE_DIR
"""
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
SCENARIO = open(os.path.join(source, "tests/regression/small_run.toml")).read().replace(
    "steps = 3000", "steps = 300")


def write(path, text):
    with open(path, "w") as f:
        f.write(text)


with tempfile.TemporaryDirectory() as tmp:
    scenario = os.path.join(tmp, "s.toml")
    write(scenario, SCENARIO)
    marker = os.path.join(tmp, "PWNED")
    names = ["O'Brien results", "a b$(touch PWNED)c", "q`touch PWNED`", "it's \"quoted\"",
             "new\nline", "semi;touch PWNED"]
    for name in names:
        out = os.path.join(tmp, name)
        r = subprocess.run([rcdem, "run", scenario, "-o", out], cwd=tmp, capture_output=True,
                           text=True, timeout=300)
        check(r.returncode == 0 and os.path.exists(os.path.join(out, "load_displacement.png"))
              and "warning" not in r.stderr,
              f"-o {name!r}: exit {r.returncode}, the plot drawn, no warning "
              f"({r.stderr.strip()[-200:] if r.returncode else ''})")
    check(not os.path.exists(marker), "no shell code in a path was run")

    # A tools/ of the user's beside the working directory.
    os.makedirs(os.path.join(tmp, "tools"))
    write(os.path.join(tmp, "tools", "plot_history.py"),
          f"open({marker + '_tools'!r}, 'w').write('ran')\n")
    out = os.path.join(tmp, "own_tool")
    r = subprocess.run([rcdem, "-q", "run", scenario, "-o", out], cwd=tmp, capture_output=True,
                       text=True, timeout=300)
    check(r.returncode == 0 and not os.path.exists(marker + "_tools")
          and os.path.exists(os.path.join(out, "load_displacement.png")),
          "a script named like rcdem's in ./tools is not run; rcdem's own plot is drawn")

    # A failing plot: a matplotlib that cannot be imported (PYTHONPATH, passed on to the tool).
    fake = os.path.join(tmp, "fake")
    os.makedirs(os.path.join(fake, "matplotlib"))
    write(os.path.join(fake, "matplotlib", "__init__.py"), "raise ImportError('test: broken')\n")
    out = os.path.join(tmp, "plot_fails")
    r = subprocess.run([rcdem, "run", scenario, "-o", out], cwd=tmp, capture_output=True,
                       text=True, timeout=300, env=dict(os.environ, PYTHONPATH=fake))
    check(r.returncode == 0 and "rcdem: warning: plotting failed (exit status 1: ImportError: "
          "test: broken; see " in r.stderr and os.path.exists(os.path.join(out, "plot.log")),
          f"a failed plot is a warning naming its cause and log, exit {r.returncode} "
          f"({[x for x in r.stderr.splitlines() if 'warning' in x]})")

    # Ctrl-C while calibrate draws figure7.png.
    out = os.path.join(tmp, "calibrate")
    p = subprocess.Popen([rcdem, "-q", "calibrate",
                          os.path.join(source, "examples/uniaxial/cube160.toml"), "--size", "0.05",
                          "--peak-only", "--rate-factor", "4", "-o", out],
                         stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                         start_new_session=True)
    seen = False
    t0 = time.time()
    while time.time() - t0 < 300 and p.poll() is None:
        kids = open(f"/proc/{p.pid}/task/{p.pid}/children").read().split()
        if any("plot_calibration" in open(f"/proc/{k}/cmdline").read() for k in kids
               if os.path.exists(f"/proc/{k}/cmdline")):
            seen = True
            os.killpg(p.pid, signal.SIGINT)
            break
        time.sleep(0.005)
    code = p.wait(timeout=120)
    check(seen, "calibrate's plotting tool was seen running as its child")
    check(code in (-signal.SIGINT, 128 + signal.SIGINT),
          f"a Ctrl-C during calibrate's plot ends calibrate by SIGINT (returncode {code})")

checks.finish()
