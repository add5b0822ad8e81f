#!/usr/bin/python3
"""Loading programs on real specimens (issue 41, item 2): examples/cyclic/beam.toml (its last
segment shortened) and examples/cyclic/pull_out.toml, with a history row every step.

  * the beam: the force-controlled hold keeps the load within 1% of its target for its whole
    duration and never passes the target by more than 1%; three unload-reload cycles each reach
    their deflection and unload to their load; the energy balance stays within 0.5% from the
    first cycle to the end; the unloading stiffness (a line fitted to each unloading branch
    between 30% and 80% of its cycle's largest load) falls as the damage grows; the run ends
    with its program (stop_reason program_end);
  * the pull-out: three slip cycles of growing amplitude, each unloaded, then pulled out;
  * a pull-out killed (SIGKILL) in mid-program after a checkpoint and resumed ends with the same
    history.csv and broken_points.csv, byte for byte, as the uninterrupted run.

usage: check_cyclic.py RCDEM_BINARY SOURCE_DIR
"""
import csv
import json
import os
import signal
import statistics
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checklist import Checklist  # noqa: E402

rcdem, source = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
checks = Checklist()
check = checks.check
EVERY_STEP = "output.history_rows=10000000"


def scenario(name):
    return os.path.join(source, "examples/cyclic", name)


def run(args):
    return subprocess.run([rcdem, "-q", "run"] + args, capture_output=True, text=True, timeout=600)


def rows(d):
    with open(os.path.join(d, "history.csv")) as f:
        return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]


def segment(h, column, k):
    return [x for x in h if x[column] == k]


def slope(branch):
    xs = [x["load_displacement_m"] for x in branch]
    ys = [x["load_N"] for x in branch]
    mx, my = statistics.mean(xs), statistics.mean(ys)
    return -sum((a - mx) * (b - my) for a, b in zip(xs, ys)) / sum((a - mx) ** 2 for a in xs)


def check_beam(tmp):
    out = os.path.join(tmp, "beam")
    r = run([scenario("beam.toml"), "-o", out, "--set", EVERY_STEP, "--set", "output.snapshots=0",
             "--set", "plates.load.program.to_failure.target=-0.0001"])
    check(r.returncode == 0, f"the cyclic beam runs (exit {r.returncode}: {r.stderr[-300:]})")
    if r.returncode:
        return
    h = rows(out)
    summary = json.load(open(os.path.join(out, "summary.json")))
    check(summary["stop_reason"] == "program_end", f"it ends with its program ({summary['stop_reason']})")
    hold = segment(h, "load_program_segment", 1)
    reached = [i for i, x in enumerate(hold) if abs(x["load_N"] - 1500.0) <= 15.0]
    held = hold[reached[0]:] if reached else []
    worst = max((abs(x["load_N"] - 1500.0) / 1500.0 for x in held), default=1.0)
    span = held[-1]["time_s"] - held[0]["time_s"] if held else 0.0
    check(held and worst <= 0.01 and span >= 0.003 - 2e-6,
          f"the force hold keeps the load within 1% of 1500 N for {span * 1e3:.3f} ms "
          f"({len(held)} steps, worst {worst:.3%})")
    check(max(x["load_N"] for x in hold) <= 1515.0,
          f"no overshoot past 1% ({max(x['load_N'] for x in hold):.1f} N at most)")
    stiffness, broken = [], []
    for k in range(3):
        peak = segment(h, "load_program_segment", 2 + 2 * k)
        unload = segment(h, "load_program_segment", 3 + 2 * k)
        # A segment ends at the step whose state meets its goal: the next one's first row.
        unloaded = segment(h, "load_program_segment", 4 + 2 * k)[0]
        target = -4e-5 - 2e-5 * k
        check(peak and unload and unload[0]["load_displacement_m"] <= target and
              unloaded["load_N"] <= 200.0,
              f"cycle {k + 1} reaches {target * 1e6:.0f} um and unloads to 200 N "
              f"({unload[0]['load_displacement_m'] * 1e6:.2f} um, {unloaded['load_N']:.0f} N)")
        fmax = max(x["load_N"] for x in peak + unload)
        branch = [x for x in unload if 0.3 * fmax <= x["load_N"] <= 0.8 * fmax]
        stiffness.append(slope(branch))
        broken.append(unload[-1]["broken_points"] + unload[-1]["damaged_points"])
    check(stiffness[2] < 0.9 * stiffness[0] and broken[2] > broken[0],
          "the unloading stiffness falls as the damage grows: "
          + ", ".join(f"{s / 1e6:.1f} MN/m at {b:.0f} damaged points"
                      for s, b in zip(stiffness, broken)))
    cycles = [x for x in h if x["load_program_segment"] >= 2]
    error = max(abs(x["energy_balance_error"]) for x in cycles)
    check(error < 0.005, f"the energy balance within 0.5% over the cycles and after ({error:.2g})")


def check_pull_out(tmp):
    out = os.path.join(tmp, "pull_out")
    r = run([scenario("pull_out.toml"), "-o", out, "--set", EVERY_STEP])
    check(r.returncode == 0, f"the cyclic pull-out runs (exit {r.returncode}: {r.stderr[-300:]})")
    if r.returncode:
        return None
    h = rows(out)
    for k in range(3):
        unload = segment(h, "bar_program_segment", 2 * k + 1)
        unloaded = segment(h, "bar_program_segment", 2 * k + 2)[0]
        check(unload[0]["bar_pull_displacement_m"] >= 2e-5 * (k + 1) and
              unloaded["load_N"] <= 1000.0,
              f"slip cycle {k + 1}: to {unload[0]['bar_pull_displacement_m'] * 1e6:.2f} um, "
              f"back to {unloaded['load_N']:.0f} N")
    check(h[-1]["bar_pull_displacement_m"] >= 3e-4, "then pulled out to 0.3 mm")
    return out


def check_resume(tmp, whole):
    killed = os.path.join(tmp, "killed")
    for attempt in range(4):
        p = subprocess.Popen([rcdem, "-q", "run", scenario("pull_out.toml"), "-o", killed,
                              "--force", "--set", EVERY_STEP, "--checkpoint-every", "3000"],
                             stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        while p.poll() is None and not any(n.endswith(".h5") for n in os.listdir(killed)
                                           if os.path.isdir(killed)):
            time.sleep(0.01)
        if p.poll() is None:
            p.send_signal(signal.SIGKILL)
            p.wait()
            break
    r = run(["--resume", killed])
    check(r.returncode == 0, f"the killed pull-out resumes (exit {r.returncode}: {r.stderr[-300:]})")
    for name in ("history.csv", "broken_points.csv"):
        same = open(os.path.join(killed, name), "rb").read() == \
            open(os.path.join(whole, name), "rb").read()
        check(same, f"resumed in mid-program, {name} is the uninterrupted run's, byte for byte")


with tempfile.TemporaryDirectory() as tmp:
    check_beam(tmp)
    whole = check_pull_out(tmp)
    if whole:
        os.makedirs(os.path.join(tmp, "killed"), exist_ok=True)
        check_resume(tmp, whole)
checks.finish()
