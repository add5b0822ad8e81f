#!/usr/bin/python3
"""Two rcdem in one directory, and replacing results (issue 28, 7), on small_run.toml made long:

  * while a run is live in DIR: `generate --force`, `run --force` and `run --resume` into DIR are
    refused naming run.lock, and the run's files stay as they were;
  * while a study runs in DIR: a second study into DIR is refused, and the first's case is intact;
  * `run --force` over a finished run that is refused during its set-up: the earlier results are
    back, byte for byte, and nothing of the refused run is left;
  * `run --force` over a finished run that fails after it started: only the new run's files
    (manifest "failed", its history), none of the earlier run's (its summary.json);
  * a `--force` killed before its run started (DIR/.rcdem-replaced left): the next command in DIR
    puts the earlier results back first;
  * `--resume` of a generate directory says it is not a run directory.

usage: check_concurrency.py RCDEM_BINARY SOURCE_DIR
"""
import json
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checklist import Checklist  # noqa: E402

rcdem, source = sys.argv[1], Path(sys.argv[2])
checks = Checklist()
check = checks.check
ENV = dict(os.environ, OMP_NUM_THREADS="1")


def run(args):
    return subprocess.run([rcdem, "-q"] + args, capture_output=True, text=True, timeout=300,
                          env=ENV)


def wait_for(predicate, seconds=120.0):
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        if predicate():
            return True
        time.sleep(0.1)
    return False


def snapshot(d: Path) -> dict:
    return {str(p.relative_to(d)): p.read_bytes() for p in sorted(d.rglob("*")) if p.is_file()}


PRESET = 'preset = "basic"'  # small_run.toml's [solver] line, after which keys are added


def scenario(tmp: Path, name: str, replace: dict) -> Path:
    text = (source / "tests/regression/small_run.toml").read_text()
    for old, new in replace.items():
        assert old in text, old
        text = text.replace(old, new)
    path = tmp / f"{name}.toml"
    path.write_text(text)
    return path


def started(d: Path):
    return lambda: (d / "particles_initial.vtu").exists() and (d / "manifest.json").exists()


def live_run_refuses_others(tmp: Path, long_run: Path, small: Path) -> None:
    d = tmp / "live"
    proc = subprocess.Popen([rcdem, "-q", "run", str(long_run), "-o", str(d)], env=ENV,
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    try:
        check(wait_for(started(d)), "a long run starts")
        before = json.loads((d / "manifest.json").read_text())
        for args in (["generate", str(small), "-o", str(d), "--force"],
                     ["run", str(small), "-o", str(d), "--force"],
                     ["run", "--resume", str(d)]):
            r = run(args)
            check(r.returncode == 1 and "another rcdem is running" in r.stderr
                  and "run.lock" in r.stderr, f"{args[0]} {args[-1]} beside the live run is "
                  f"refused: {r.returncode} {r.stderr.strip()[:160]!r}")
        after = json.loads((d / "manifest.json").read_text())
        check(after["exit_state"] == "running" and after["start_time"] == before["start_time"]
              and proc.poll() is None and not (d / "summary.json").exists()
              and not (d / ".rcdem-replaced").exists(),
              "the live run goes on, its files untouched")
    finally:
        proc.send_signal(signal.SIGTERM)
        proc.wait(timeout=120)
    check(proc.returncode == 128 + signal.SIGTERM, f"the run stops on SIGTERM ({proc.returncode})")


def second_study_refused(tmp: Path, long_run: Path) -> None:
    cases = tmp / "study_cases"
    cases.mkdir()
    shutil.copy(long_run, cases / "LONG.toml")
    d = tmp / "study"
    first = subprocess.Popen([rcdem, "-q", "study", "x", "--scenarios", str(cases), "-o", str(d)],
                             env=ENV, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    try:
        case = d / "cases" / "LONG"
        check(wait_for(started(case)), "a study's case starts")
        r = run(["study", "x", "--scenarios", str(cases), "-o", str(d)])
        check(r.returncode != 0 and "another rcdem is running" in r.stderr,
              f"a second study into the same directory is refused: {r.stderr.strip()[:160]!r}")
        manifest = json.loads((case / "manifest.json").read_text())
        check(manifest["exit_state"] == "running" and (case / "run.lock").exists(),
              "the first study's case is intact and running")
    finally:
        first.send_signal(signal.SIGTERM)
        first.wait(timeout=120)


def replaced_results(tmp: Path, small: Path, refused: Path, failing: Path) -> None:
    d = tmp / "replace"
    r = run(["run", str(small), "-o", str(d)])
    check(r.returncode == 0, f"a small run finishes ({r.stderr.strip()[-160:]!r})")
    before = snapshot(d)
    r = run(["run", str(refused), "-o", str(d), "--force"])
    check(r.returncode == 1 and "below 1e-12 s" in r.stderr, "a run refused at set-up fails")
    check(snapshot(d) == before, "... and the earlier results are back, byte for byte")

    r = run(["run", str(failing), "-o", str(d), "--force"])
    check(r.returncode == 1 and f"{failing}: numerical instability" in r.stderr,
          f"a run failing after its start fails: {r.stderr.strip()[:120]!r}")
    manifest = json.loads((d / "manifest.json").read_text())
    check(manifest["exit_state"] == "failed" and not (d / "summary.json").exists()
          and not (d / ".rcdem-replaced").exists() and (d / "history.csv").exists()
          and manifest["scenario"] == str(failing),
          "... and the directory holds the failed run alone, not the earlier one's summary")

    # A --force killed between setting the earlier results aside and its run's start.
    # As rcdem does it: the journal of the entries to move first, then the moves.
    failed_run = snapshot(d)
    aside = d / ".rcdem-replaced"
    aside.mkdir()
    moved = [p for p in d.iterdir() if p.name not in (".rcdem-replaced", "run.lock",
                                                       ".rcdem-outputs")]
    (aside / ".rcdem-journal").write_text("".join(p.name + "\n" for p in moved))
    for p in moved:
        p.rename(aside / p.name)
    (d / "particles.vtu").write_text("from the killed command\n")
    r = run(["generate", str(small), "-o", str(d)])
    check(r.returncode == 1 and "not empty" in r.stderr, "the next command finds DIR not empty")
    check(snapshot(d) == failed_run and not aside.exists(),
          "... after putting the set-aside results back and removing the killed command's file")

    g = tmp / "generated"
    check(run(["generate", str(small), "-o", str(g)]).returncode == 0, "a generate directory")
    r = run(["run", "--resume", str(g)])
    check(r.returncode == 1 and "not a run directory" in r.stderr,
          f"--resume of it: not a run directory ({r.stderr.strip()[:120]!r})")


def main() -> None:
    tmp = Path(tempfile.mkdtemp(prefix="rcdem_concurrency_"))
    try:
        long_run = scenario(tmp, "long", {"steps = 3000": "steps = 100000000"})
        small = scenario(tmp, "small", {"steps = 3000": "steps = 200"})
        refused = scenario(tmp, "refused", {'interface = "NL-A"': 'interface = "NL-A"\n'
                                            'density = 1e-12'})
        failing = scenario(tmp, "failing", {PRESET: PRESET + "\nmass_scaling = 1e8"})
        live_run_refuses_others(tmp, long_run, small)
        second_study_refused(tmp, long_run)
        replaced_results(tmp, small, refused, failing)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    checks.finish()


if __name__ == "__main__":
    main()
