#!/usr/bin/python3
"""`--force` deletes only what rcdem wrote (issue 44, class 1; docs/checkpoint.md, "What --force
touches"). With tests/regression/small_run.toml cut to a few steps:

  * a folder of inputs (the scenario, a sibling scenario, notes) given as `-o` with --force is
    refused and left byte for byte as it was; so is a folder holding only the scenario;
  * an rcdem run directory holding a file rcdem does not write is refused, naming that file;
  * a scenario that lies inside the results --force would replace is refused;
  * an rcdem run directory is replaced by --force, with nothing left aside;
  * an entry that cannot be moved aside (a mount point, where the machine allows mounting) fails
    the command with every earlier result still there;
  * a --force killed while it was moving the earlier results aside (the directory as such a kill
    leaves it) is put back whole by the next command, and by `--resume`.

usage: check_force.py RCDEM_BINARY SOURCE_DIR
"""
import hashlib
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checklist import Checklist  # noqa: E402

rcdem, source = sys.argv[1], sys.argv[2]
checks = Checklist()
check = checks.check
SCENARIO = open(os.path.join(source, "tests/regression/small_run.toml")).read().replace(
    "steps = 3000", "steps = 200")


def run(args, **kw):
    return subprocess.run([rcdem, "-q"] + args, capture_output=True, text=True, timeout=300, **kw)


def tree(d):
    """Every file under d with its content's hash, every directory by name."""
    out = {}
    for root, dirs, files in os.walk(d):
        for x in dirs:
            out[os.path.relpath(os.path.join(root, x), d)] = "dir"
        for x in files:
            p = os.path.join(root, x)
            out[os.path.relpath(p, d)] = hashlib.sha256(open(p, "rb").read()).hexdigest()
    return out


def write(path, text):
    with open(path, "w") as f:
        f.write(text)


def finished_run(d):
    os.makedirs(d, exist_ok=True)
    scenario = os.path.join(os.path.dirname(d), os.path.basename(d) + ".toml")
    write(scenario, SCENARIO)
    r = run(["run", scenario, "-o", d, "--force"] if os.listdir(d) else ["run", scenario, "-o", d])
    assert r.returncode == 0, r.stderr
    return scenario


with tempfile.TemporaryDirectory() as tmp:
    # A folder of inputs.
    inputs = os.path.join(tmp, "inputs")
    os.makedirs(inputs)
    write(os.path.join(inputs, "scenario.toml"), SCENARIO)
    write(os.path.join(inputs, "sibling.toml"), SCENARIO)
    write(os.path.join(inputs, "notes.txt"), "my notes\n")
    before = tree(inputs)
    r = run(["run", os.path.join(inputs, "scenario.toml"), "-o", inputs, "--force"])
    check(r.returncode != 0 and "rcdem: error:" in r.stderr and "--force replaces only" in r.stderr,
          f"a folder of inputs is refused with --force (exit {r.returncode}: "
          f"{r.stderr.strip()[:160]})")
    check(tree(inputs) == before, "the folder of inputs is left as it was, byte for byte")

    only = os.path.join(tmp, "only_scenario")
    os.makedirs(only)
    write(os.path.join(only, "scenario.toml"), SCENARIO)
    before = tree(only)
    r = run(["run", os.path.join(only, "scenario.toml"), "-o", only, "--force"])
    check(r.returncode != 0 and "no results of rcdem" in r.stderr,
          f"a folder holding only its scenario is refused ({r.stderr.strip()[:160]})")
    check(tree(only) == before, "the scenario in it is untouched")

    before = tree(inputs)
    for cmd in ("generate", "calibrate"):
        r = run([cmd, os.path.join(inputs, "scenario.toml"), "-o", inputs, "--force"])
        check(r.returncode == 1 and "--force replaces only" in r.stderr and tree(inputs) == before,
              f"`{cmd} --force` on the folder of inputs is refused too, nothing touched")

    # An rcdem run directory with a file of the user's in it.
    runs = os.path.join(tmp, "runs")
    os.makedirs(runs)
    rd = os.path.join(runs, "a")
    scenario = finished_run(rd)
    write(os.path.join(rd, "my_notes.txt"), "keep me\n")
    before = tree(rd)
    r = run(["run", scenario, "-o", rd, "--force"])
    check(r.returncode != 0 and "'my_notes.txt'" in r.stderr,
          f"a run directory holding a user's file is refused, naming it ({r.stderr.strip()[:160]})")
    check(tree(rd) == before, "that run directory is left as it was")
    os.remove(os.path.join(rd, "my_notes.txt"))

    # The scenario to run lies among the results.
    before = tree(rd)
    r = run(["run", os.path.join(rd, "scenario.toml"), "-o", rd, "--force"])
    check(r.returncode != 0 and "among the results" in r.stderr,
          f"a scenario inside the results to replace is refused ({r.stderr.strip()[:160]})")
    check(tree(rd) == before, "and nothing is touched")

    # The ordinary case still works.
    r = run(["run", scenario, "-o", rd, "--force"])
    names = set(os.listdir(rd))
    check(r.returncode == 0 and "summary.json" in names and ".rcdem-replaced" not in names
          and ".rcdem-replaced.delete" not in names,
          f"--force replaces an rcdem run directory (exit {r.returncode}), nothing left aside")

    # An entry that cannot be moved aside: a mount point named like rcdem's snapshots.
    rd2 = os.path.join(runs, "b")
    scenario2 = finished_run(rd2)
    snaps = os.path.join(rd2, "snapshots")
    kept = os.path.join(tmp, "snapshots_kept")
    shutil.move(snaps, kept)
    os.makedirs(snaps)
    mounted = subprocess.run(["mount", "-t", "tmpfs", "none", snaps],
                             capture_output=True).returncode == 0
    if mounted:
        try:
            for f in os.listdir(kept):
                shutil.copy(os.path.join(kept, f), snaps)
            before = tree(rd2)
            r = run(["run", scenario2, "-o", rd2, "--force"])
            after = tree(rd2)
        finally:
            subprocess.run(["umount", snaps])
        check(r.returncode != 0 and "cannot set 'snapshots' aside" in r.stderr,
              f"an entry that cannot be moved aside fails the command ({r.stderr.strip()[:160]})")
        check(after == before, "every earlier result is still there, with its contents "
              f"({len(before)} entries)")
    else:
        print("skipped: mounting is not allowed here (the mount-point check)")

    # A --force killed while moving aside: some earlier results moved, the rest not.
    rd3 = os.path.join(runs, "c")
    scenario3 = finished_run(rd3)
    before = tree(rd3)
    aside = os.path.join(rd3, ".rcdem-replaced")
    os.makedirs(aside)
    earlier = sorted(n for n in os.listdir(rd3) if n not in (".rcdem-outputs", ".rcdem-replaced"))
    write(os.path.join(aside, ".rcdem-journal"), "".join(n + "\n" for n in earlier))
    for n in earlier[:3]:
        os.rename(os.path.join(rd3, n), os.path.join(aside, n))
    r = run(["generate", scenario3, "-o", rd3])
    check(r.returncode != 0 and tree(rd3) == before,
          f"the next command puts a half-moved replacement back whole (moved: {earlier[:3]}) "
          "and then refuses the non-empty directory")
    # The same state, then --resume of a run killed during its set-up under --force.
    rd4 = os.path.join(runs, "d")
    os.makedirs(rd4)
    write(os.path.join(tmp, "d_long.toml"), SCENARIO.replace("steps = 200", "steps = 3000"))
    p = subprocess.Popen([rcdem, "-q", "run", os.path.join(tmp, "d_long.toml"), "-o", rd4,
                          "--checkpoint-every", "100"],
                         stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    t0 = time.time()
    while time.time() - t0 < 120 and p.poll() is None:
        if any(n.startswith("checkpoint_") for n in os.listdir(rd4)):
            p.send_signal(signal.SIGINT)
            break
        time.sleep(0.02)
    p.wait(timeout=120)
    before = tree(rd4)
    os.makedirs(os.path.join(rd4, ".rcdem-replaced"))
    moved = sorted(n for n in os.listdir(rd4) if n not in (".rcdem-outputs", ".rcdem-replaced"))
    write(os.path.join(rd4, ".rcdem-replaced", ".rcdem-journal"), "".join(n + "\n" for n in moved))
    for n in moved:
        os.rename(os.path.join(rd4, n), os.path.join(rd4, ".rcdem-replaced", n))
    write(os.path.join(rd4, "scenario.toml"), "# the killed command's copy\n")
    r = run(["run", "--resume", rd4, "--checkpoint-every", "0"])
    check("restored" in r.stderr or r.returncode == 0,
          f"--resume after a --force killed in its set-up restores the earlier run first "
          f"(exit {r.returncode}: {r.stderr.strip()[-200:]})")
    check(r.returncode == 0 and os.path.exists(os.path.join(rd4, "summary.json")),
          "and the restored run resumes to its end")

checks.finish()
