#!/usr/bin/python3
"""`--resume` never hangs and never loses its way (issue 44, class 4), on
tests/regression/small_run.toml interrupted after its first checkpoints:

  * a FIFO named like the newest checkpoint: rejected ("not a regular file"), the previous
    checkpoint taken, the run completes (no hang: each resume has 60 s);
  * a huge sparse file named like the newest checkpoint, with a checkpoint's first bytes or with
    none: rejected with the reason, no out-of-memory, the run completes;
  * a run killed between writing summary.json and its manifest's last update: --resume completes
    the manifest ("finished", checkpoints removed) and exits 0;
  * an unreadable manifest.json: a warning, the damaged file kept beside, the run resumes;
  * the run directory's own scenario.toml edited: the refusal names that file.
(A --force interrupted during its set-up, then --resume: check_force.py.)

usage: check_resume_edges.py RCDEM_BINARY SOURCE_DIR
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checklist import Checklist  # noqa: E402
from interrupted_run import checkpoints, interrupted_run as interrupted  # noqa: E402

rcdem, source = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
checks = Checklist()
check = checks.check
SCENARIO = open(os.path.join(source, "tests/regression/small_run.toml")).read()


def resume(d):
    try:
        return subprocess.run([rcdem, "-q", "run", "--resume", d], capture_output=True, text=True,
                              timeout=60)
    except subprocess.TimeoutExpired:
        return None


def interrupted_run(tmp, name):
    return interrupted(rcdem, SCENARIO, tmp, name)


with tempfile.TemporaryDirectory() as tmp:
    d, _ = interrupted_run(tmp, "fifo")
    fifo = os.path.join(d, "checkpoint_999999999999.h5")
    os.mkfifo(fifo)
    r = resume(d)
    check(r is not None and r.returncode == 0 and "not a regular file" in r.stderr,
          "a FIFO named like the newest checkpoint: no hang, rejected, the run completes "
          f"({'timed out' if r is None else r.returncode})")

    for kind in ("with a checkpoint's header", "of zeros"):
        d, _ = interrupted_run(tmp, "sparse" + str(len(kind)))
        head = open(checkpoints(d)[-1], "rb").read(24)
        huge = os.path.join(d, "checkpoint_999999999999.h5")
        with open(huge, "wb") as f:
            if kind.startswith("with"):
                size = 1 << 40
                f.write(head[:16] + size.to_bytes(8, "little"))
            f.truncate(1 << 40)
        r = resume(d)
        check(r is not None and r.returncode == 0 and "999999999999" in r.stderr
              and "rejected" in r.stderr,
              f"a 1 TB sparse file {kind} named like a checkpoint: rejected, the run completes "
              f"({'timed out' if r is None else (r.returncode, r.stderr.strip()[-160:])})")

    # Killed between summary.json and the manifest's last update.
    d, _ = interrupted_run(tmp, "half_finished")
    r = resume(d)
    assert r.returncode == 0
    m = json.load(open(os.path.join(d, "manifest.json")))
    m["exit_state"] = "running"
    m["sessions"][-1]["exit_state"] = "running"
    json.dump(m, open(os.path.join(d, "manifest.json"), "w"))
    shutil.copy(os.path.join(d, "summary.json"), os.path.join(tmp, "summary.json"))
    open(os.path.join(d, "checkpoint_000000000200.h5"), "wb").write(b"left by the kill")
    r = resume(d)
    m = json.load(open(os.path.join(d, "manifest.json")))
    check(r.returncode == 0 and m["exit_state"] == "finished" and m["end_time"]
          and m["sessions"][-1]["exit_state"] == "finished" and not checkpoints(d)
          and open(os.path.join(d, "summary.json")).read() ==
          open(os.path.join(tmp, "summary.json")).read(),
          f"a run killed before its manifest's last update: --resume completes it (exit "
          f"{r.returncode}, manifest {m['exit_state']}, {len(checkpoints(d))} checkpoints left)")

    # An unreadable manifest.
    d, _ = interrupted_run(tmp, "manifest")
    open(os.path.join(d, "manifest.json"), "w").write("{ not json")
    r = resume(d)
    check(r.returncode == 0 and "manifest.json is damaged" in r.stderr
          and os.path.exists(os.path.join(d, "manifest.json.damaged"))
          and os.path.exists(os.path.join(d, "summary.json")),
          f"a damaged manifest.json: a warning, kept as manifest.json.damaged, the run resumes "
          f"(exit {r.returncode})")

    # The run directory's own scenario edited.
    d, scenario = interrupted_run(tmp, "edited")
    copy = os.path.join(d, "scenario.toml")
    open(copy, "a").write("# edited\n")
    r = resume(d)
    check(r.returncode == 1 and f"'{copy}' changed" in r.stderr,
          f"an edited run-directory scenario.toml is named in the refusal "
          f"({r.stderr.strip()[-200:]})")

checks.finish()
