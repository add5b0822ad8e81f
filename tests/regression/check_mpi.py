#!/usr/bin/python3
"""The distributed run (issue 46, docs/parallel.md) against one process, with the `mpi` build:

  * `mpirun -np 2` and `-np 3 rcdem run` give the same history.csv, broken_points.csv, every
    snapshot file and summary.json (but its wall-clock fields) as `rcdem run` on: the quick AN2
    NL-B beam past its first crack (15,000 steps, past the cracking peak near step 12,800: two
    bars, their interfaces and nodes, three plates), the pull-out of a bar with the NL-B
    interface, the tension cube past its peak; on 3 ranks also without the condensation of
    intact contacts, and the cyclic pull-out (a loading program); on 2 ranks the plain
    four-point beam (two load plates, a gauge as the test's displacement: read every step);
  * a 2-rank run stopped by SIGINT after a checkpoint, resumed on 3 ranks, and another resumed on
    one process, end with the same outputs as the uninterrupted run (the checkpoint holds damaged
    contacts held to their sums, gathered from both ranks: format 8 on); the tension cube with
    softening contacts held, resumed on 3 ranks (its checkpoint holds their clocks: format 9);
  * a bad scenario under `mpirun -q` (without -q mpirun adds its own note on the exit code): one
    error line (from rank 0), a non-zero exit, within seconds; another command than `run`:
    refused in one line;
  * a rank killed (SIGKILL) during the run: mpirun ends every rank within seconds, non-zero, and
    rank 0 says so in one line (mpi/peer_watch: the launcher's SIGTERM came while it waited for
    the rank that is gone).

The ranks are oversubscribed (2 cores run 3 ranks); each rank runs one thread.

usage: check_mpi.py RCDEM_BINARY MPIEXEC SOURCE_DIR
"""
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time

import h5py

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checklist import Checklist  # noqa: E402

rcdem, mpiexec, source = sys.argv[1], sys.argv[2], sys.argv[3]
checks = Checklist()


def check(cond, what, detail=""):
    checks.check(cond, what if cond or not detail else f"{what}: {detail}")


WALL_CLOCK = {"seconds", "loop_seconds", "steps_per_second", "step_seconds", "threads"}
# summary.json's record of the ranks (their count, rank 0's time in exchanges): the run's own.
WALL_CLOCK.add("distributed")
CKPT = re.compile(r"^checkpoint_(\d{12})\.h5$")
# Open MPI as root needs the first option; the others let 3 ranks share 2 cores without binding.
MPI_OPTIONS = ["--allow-run-as-root", "--oversubscribe", "--bind-to", "none"]

# name: scenario, extra options, the rank counts compared with one process.
CASES = {
    "quick_AN2_NL-B": ("examples/three_point_bending/study/quick/AN2_NL-B.toml",
                       ["--set", "stop.steps=15000"], (2, 3)),
    "pull_out_NL-B": ("examples/pull_out/NL-B.toml", [], (2, 3)),
    "tension_cube": ("tests/golden/scenarios/tension_cube60.toml", [], (2, 3)),
    # Every contact through its points (no condensation): the dissipation per contact.
    "tension_cube_points": ("tests/golden/scenarios/tension_cube60.toml",
                            ["--set", "solver.condense_elastic_contacts=false"], (3,)),
    # Only contacts whose points stay inside their envelopes held (softening ones visited).
    "tension_cube_unloading": ("tests/golden/scenarios/tension_cube60.toml",
                               ["--set", "solver.hold_softening_contacts=false"], (2,)),
    "cyclic_pull_out": ("examples/cyclic/pull_out.toml", [], (3,)),
    # Two load plates and a gauge as the test's displacement: rank 0 reads the gauge's particles
    # every step, so it gathers every particle's motion every step.
    "four_point_plain": ("examples/four_point_bending/plain.toml",
                         ["--set", "stop.steps=3000"], (2,)),
}


def env():
    e = dict(os.environ)
    e["OMP_NUM_THREADS"] = "1"
    e["OMPI_MCA_mpi_yield_when_idle"] = "1"  # oversubscribed: waiting ranks give up the core
    return e


def command(ranks, args, launcher=()):
    base = [rcdem, "-q"] + args + (["--threads", "1"] if args[0] == "run" else [])
    if ranks == 1:
        return base
    return [mpiexec] + list(launcher) + MPI_OPTIONS + ["-np", str(ranks)] + base


def run(ranks, args, timeout=900, launcher=()):
    return subprocess.run(command(ranks, args, launcher), capture_output=True, text=True,
                          timeout=timeout, env=env())


def outputs(d):
    """Every output file's bytes but summary.json and the manifest, and summary.json's fields."""
    files = {}
    for name in ["history.csv", "broken_points.csv"]:
        with open(os.path.join(d, name), "rb") as f:
            files[name] = f.read()
    snaps = os.path.join(d, "snapshots")
    for name in sorted(os.listdir(snaps)):
        with open(os.path.join(snaps, name), "rb") as f:
            files["snapshots/" + name] = f.read()
    with open(os.path.join(d, "summary.json")) as f:
        summary = {k: v for k, v in json.load(f).items() if k not in WALL_CLOCK}
    return files, summary


def same_outputs(a, b):
    fa, sa = outputs(a)
    fb, sb = outputs(b)
    differ = sorted(k for k in set(fa) | set(fb) if fa.get(k) != fb.get(k))
    fields = sorted(k for k in set(sa) | set(sb) if sa.get(k) != sb.get(k))
    return not differ and not fields, f"files differing: {differ[:5]}; summary fields: {fields}"


def bitwise(tmp):
    for name, (scenario, extra, counts) in CASES.items():
        path = os.path.join(source, scenario)
        ref = os.path.join(tmp, name + "_1")
        r = run(1, ["run", path, "-o", ref] + extra)
        check(r.returncode == 0, f"{name}: one process runs", r.stderr[-400:])
        for ranks in counts:
            out = os.path.join(tmp, f"{name}_{ranks}")
            t0 = time.time()
            r = run(ranks, ["run", path, "-o", out] + extra)
            ok = r.returncode == 0
            check(ok, f"{name}: {ranks} ranks run ({time.time() - t0:.0f} s)", r.stderr[-400:])
            if ok:
                same, why = same_outputs(ref, out)
                check(same, f"{name}: {ranks} ranks give the same bits as one process", why)


def checkpoints(d):
    if not os.path.isdir(d):
        return []
    return sorted(int(m.group(1)) for f in os.listdir(d) if (m := CKPT.match(f)))


def interrupted_run(out, scenario, extra, every):
    """A 2-rank run stopped by SIGINT once it has written a checkpoint past step 0."""
    p = subprocess.Popen(command(2, ["run", scenario, "-o", out, "--checkpoint-every", str(every)] +
                                 extra), stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                         text=True, env=env())
    t0 = time.time()
    while time.time() - t0 < 300 and p.poll() is None and not checkpoints(out):
        time.sleep(0.05)
    p.send_signal(signal.SIGINT)
    _, err = p.communicate(timeout=120)
    return p.returncode, err


# Resumed runs: a case of CASES (its uninterrupted 1-process run is bitwise()'s reference), the
# rank counts that resume its 2-rank checkpoint, the checkpoints' interval (the cube cracks after
# step 2,000) and the checkpoint's section that must not be empty.
RESUMES = [
    ("pull_out_NL-B", (3, 1), 2000, "contacts.held"),
    # Softening contacts held with their clocks (docs/model.md): the clocks travel with the
    # contacts' owners.
    ("tension_cube", (3,), 5000, "contacts.held.clock"),
]


def resume_other_rank_count(tmp):
    for name, counts, every, section in RESUMES:
        scenario, extra, _ = CASES[name]
        scenario = os.path.join(source, scenario)
        ref = os.path.join(tmp, name + "_1")
        for ranks in counts:
            out = os.path.join(tmp, f"resume_{name}_2_to_{ranks}")
            code, err = interrupted_run(out, scenario, extra, every)
            check(code != 0 and checkpoints(out),
                  f"{name}: a 2-rank run stops on SIGINT with a checkpoint (exit {code}, "
                  f"checkpoints {checkpoints(out)})", err[-400:])
            rows = 0
            if checkpoints(out):
                last = os.path.join(out, f"checkpoint_{checkpoints(out)[-1]:012d}.h5")
                with h5py.File(last, "r") as f:
                    rows = f[section + "/contact"].shape[0]
            check(rows > 0, f"{name}: the 2-rank checkpoint's {section} has rows ({rows})")
            r = run(ranks, ["run", "--resume", out])
            check(r.returncode == 0, f"{name}: the 2-rank checkpoint resumes on {ranks} rank(s)",
                  r.stderr[-400:])
            if r.returncode == 0:
                same, why = same_outputs(ref, out)
                check(same, f"{name}: resumed on {ranks} rank(s), the same bits as the "
                      "uninterrupted run", why)


def failures(tmp):
    bad = os.path.join(tmp, "bad.toml")
    with open(bad, "w") as f:
        f.write('[specimen]\nshape = "box"\nsize = [0.05, 0.05, "wide"]\n')
    t0 = time.time()
    # mpirun -q: without it, mpirun adds its own note on the exit code below rcdem's line.
    r = run(3, ["run", bad, "-o", os.path.join(tmp, "bad_out")], timeout=60, launcher=["-q"])
    lines = [ln for ln in r.stderr.splitlines() if ln.strip()]
    check(r.returncode != 0 and len(lines) == 1 and "bad.toml" in lines[0] and
          time.time() - t0 < 30,
          f"a bad scenario on 3 ranks: one line naming the file, exit {r.returncode}, "
          f"{time.time() - t0:.1f} s", r.stderr[-600:])
    r = run(2, ["generate", os.path.join(source, "examples/pull_out/NL-B.toml"), "-o",
                os.path.join(tmp, "gen")], timeout=60, launcher=["-q"])
    lines = [ln for ln in r.stderr.splitlines() if ln.strip()]
    check(r.returncode != 0 and len(lines) == 1 and "only 'rcdem run'" in lines[0],
          "another command on 2 ranks is refused in one line", r.stderr[-400:])


def rank_pids(mpirun_pid):
    """The processes mpirun started, with their ranks (from their environment)."""
    found = {}
    for pid in os.listdir("/proc"):
        if not pid.isdigit():
            continue
        try:
            with open(f"/proc/{pid}/stat") as f:
                ppid = int(f.read().rsplit(")", 1)[1].split()[1])
            if ppid != mpirun_pid:
                continue
            with open(f"/proc/{pid}/environ", "rb") as f:
                for item in f.read().split(b"\0"):
                    if item.startswith(b"OMPI_COMM_WORLD_RANK="):
                        found[int(item.split(b"=")[1])] = int(pid)
        except (OSError, ValueError, IndexError):
            continue
    return found


def killed_rank(tmp):
    scenario = os.path.join(source, "examples/three_point_bending/study/quick/AN2_NL-B.toml")
    p = subprocess.Popen(command(3, ["run", scenario, "-o", os.path.join(tmp, "killed")],
                                 launcher=("-q",)),
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env())
    t0 = time.time()
    ranks = {}
    while time.time() - t0 < 60 and p.poll() is None and len(ranks) < 3:
        ranks = rank_pids(p.pid)
        time.sleep(0.2)
    time.sleep(3)  # into the loop
    if 1 in ranks:
        os.kill(ranks[1], signal.SIGKILL)
    t1 = time.time()
    try:
        _, err = p.communicate(timeout=30)
    except subprocess.TimeoutExpired:
        p.kill()
        _, err = p.communicate()
    def alive():
        out = []
        for pid in ranks.values():
            try:
                with open(f"/proc/{pid}/stat") as f:
                    if f.read().rsplit(")", 1)[1].split()[0] != "Z":
                        out.append(pid)
            except OSError:
                pass
        return out
    left = alive()
    while left and time.time() - t1 < 30:  # mpirun may return while its last ranks are dying
        time.sleep(0.1)
        left = alive()
    check(1 in ranks and p.returncode not in (0, None) and time.time() - t1 < 30 and not left,
          f"rank 1 killed: every rank ends ({time.time() - t1:.1f} s, exit {p.returncode}, "
          f"left {left})")
    # Open MPI may add its own note from a rank whose shared-memory read met the lost one
    # ("[host:pid] Read -1, expected N, errno = 3"): rcdem's lines are those it starts with "rcdem".
    lines = [line for line in err.splitlines() if line.startswith("rcdem")]
    check(len(lines) == 1 and lines[0].startswith("rcdem: error: stopped by SIGTERM while rank 0")
          and "one of them has ended" in lines[0] and "--resume" in lines[0],
          f"... with one error line from rank 0 (mpirun -q): {lines}")


def main():
    tmp = tempfile.mkdtemp(prefix="rcdem_mpi_")
    try:
        bitwise(tmp)
        resume_other_rank_count(tmp)
        failures(tmp)
        killed_rank(tmp)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    checks.finish()


if __name__ == "__main__":
    sys.exit(main())
