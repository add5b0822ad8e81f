#!/usr/bin/python3
"""A seeded mutation fuzzer over rcdem's own scenarios (issue 28).

Each mutation takes one base scenario (the small test scenarios, the pull-out and golden cubes,
the quick study's beams, and the bad inputs), changes it in one or two ways, and runs
`rcdem generate` or `rcdem run` on it. The mutations:

  type       a value replaced by one of another type (string, bool, integer, array, table);
  magnitude  a number scaled by 1e-320 ... 1e300, negated, zeroed, made nan or inf;
  structure  a key or section deleted, an unknown key added, a plate or bar duplicated under a
             new name, a section renamed;
  include    an include of a missing file, a directory, "", /dev/zero, a FIFO, an empty or
             garbage file, the calibrated fragment, the file itself;
  geometry   bars crossing, identical or through the notch; plates stacked on one face; a plate
             moving off its face; a control plate that does not exist;
  text       the text truncated, a byte changed, a line nested 10,000 levels deep.

For the runs to stay short, every base first gets relaxation_iterations <= 20 and stop.steps =
300 (a mutation may change them back). Each outcome is classified:

  ok-exit-0       exit 0 and every number in summary.json and history.csv finite;
  ok-refused      exit 1 with exactly one line 'rcdem: error: ...' naming the scenario or the
                  included file;
  ok-interrupted  still running after --timeout s, then ended by SIGTERM as rcdem documents it
                  (exit 143, a checkpoint or nothing yet): a long run, not a hang (a run whose
                  loop had just ended finishes instead: exit 0, judged as such);
  CRASH           a signal, or exit 3 (internal error) other than memory;
  MEMORY          the address-space cap (--memory-gib) reached (std::bad_alloc);
  HANG            no exit within --timeout s plus 30 s after SIGTERM;
  NONFINITE       exit 0 with nan or inf in the outputs;
  BAD-MESSAGE     any other exit, or an error that is not one clear line naming the file.

Prints a line per failure and a table of counts; exits 1 if any failure, 2 on bad usage.

usage: fuzz_scenarios.py RCDEM SOURCE_DIR [--count N] [--seed S] [--jobs J] [--timeout T]
                         [--memory-gib G] [--keep DIR] [--verbose]
"""
from __future__ import annotations

import argparse
import collections
import json
import math
import os
import random
import resource
import shutil
import signal
import subprocess
import sys
import tempfile
import tomllib
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fuzz_mutations as mut  # noqa: E402

PREFIX = "rcdem: error: "
FAILURES = ("CRASH", "MEMORY", "HANG", "NONFINITE", "BAD-MESSAGE")


def bases(source: Path) -> list[tuple[str, dict, bool]]:
    """(name, parsed TOML, whether it is a bad input) of every base scenario, made short."""
    files = sorted((source / "tests/regression").glob("small_*.toml"))
    files += sorted((source / "tests/golden/scenarios").glob("*.toml"))
    files += sorted((source / "examples/pull_out").glob("*.toml"))
    files += sorted((source / "examples/three_point_bending/study/quick").glob("AN[02]*.toml"))
    bad = sorted((source / "tests/bad_input").glob("*.toml"))
    out = []
    for f in files + bad:
        try:
            doc = tomllib.loads(f.read_text())
        except (tomllib.TOMLDecodeError, UnicodeDecodeError):
            continue  # the bad inputs that are not TOML: their text is mutated elsewhere
        if "include" in doc:  # relative to the file: make it absolute
            inc = doc["include"]
            doc["include"] = ([str((f.parent / i).resolve()) for i in inc]
                              if isinstance(inc, list) else str((f.parent / inc).resolve()))
        gen = doc.setdefault("generation", {})
        if isinstance(gen, dict):
            gen["relaxation_iterations"] = min(20, gen.get("relaxation_iterations", 20)
                                               if isinstance(gen.get("relaxation_iterations"),
                                                             int) else 20)
        if "plates" in doc:
            doc["stop"] = {"steps": 300}
            doc.setdefault("output", {})["snapshots"] = 2
        out.append((f.name, doc, f in bad))
    return out


def limit_memory(cap: int):
    def apply():
        resource.setrlimit(resource.RLIMIT_AS, (cap, cap))
        os.setsid()
    return apply


def finite_outputs(out: Path) -> str | None:
    """None if every number rcdem wrote is finite, else where it is not."""
    summary = out / "summary.json"
    if summary.exists():
        bad = []

        def walk(x, path):
            if isinstance(x, float) and not math.isfinite(x):
                bad.append(path)
            elif isinstance(x, dict):
                for k, v in x.items():
                    walk(v, f"{path}.{k}")
            elif isinstance(x, list):
                for i, v in enumerate(x):
                    walk(v, f"{path}[{i}]")
        walk(json.loads(summary.read_text(), parse_constant=lambda c: float(c)), "summary")
        if bad:
            return f"non-finite {bad[:3]}"
    history = out / "history.csv"
    if history.exists():
        for n, line in enumerate(history.read_text().splitlines()[1:], 2):
            for v in line.split(","):
                low = v.strip().lower()
                if "nan" in low or "inf" in low:
                    return f"history.csv line {n}: {v}"
    return None


def classify(rc, stderr: str, out: Path, names: list[str], timed_out: bool) -> tuple[str, str]:
    lines = stderr.rstrip("\n").split("\n") if stderr.strip() else []
    if timed_out:
        if rc is None:
            return "HANG", "no exit after SIGTERM"
        if rc in (143, -signal.SIGTERM):
            return "ok-interrupted", ""
        if rc != 0:
            return "BAD-MESSAGE", f"after SIGTERM: exit {rc}: {stderr[-200:]!r}"
        # The run's loop had ended as the signal came, so it finished and wrote its results.
    if rc < 0:
        return "CRASH", f"signal {-rc}: {stderr[-300:]!r}"
    if "bad_alloc" in stderr:
        return "MEMORY", stderr[-300:]
    if rc == 3:
        return "CRASH", f"internal error: {stderr[-300:]!r}"
    if rc == 0:
        reason = finite_outputs(out)
        return ("NONFINITE", reason) if reason else ("ok-exit-0", "")
    errors = [ln for ln in lines if ln.startswith(PREFIX)]
    if rc != 1 or len(errors) != 1 or not errors[0].strip()[len(PREFIX):]:
        return "BAD-MESSAGE", f"exit {rc}: {stderr[-300:]!r}"
    if not any(n in errors[0] for n in names):
        return "BAD-MESSAGE", f"names no file: {errors[0][:300]!r}"
    return "ok-refused", errors[0][len(PREFIX):][:200]


def run_one(rcdem: str, work: Path, index: int, rng: random.Random, base_list, args):
    # Most mutations start from a scenario that runs; one in six from a bad input.
    bad = rng.random() < 1 / 6
    name, doc, _ = rng.choice([b for b in base_list if b[2] == bad])
    case = work / f"m{index:05d}"
    case.mkdir()
    text, kinds, extra_names = mut.mutate(doc, rng, case)
    scenario = case / "scenario.toml"
    scenario.write_bytes(text)
    command = "run" if "plates" in doc and rng.random() < 0.6 else "generate"
    out = case / "out"
    proc = subprocess.Popen(
        [rcdem, "-q", command, str(scenario), "-o", str(out), "--force"]
        + (["--checkpoint-every", "0"] if command == "run" else []),
        stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
        env=dict(os.environ, OMP_NUM_THREADS="1"), preexec_fn=limit_memory(args.memory))
    timed_out = False
    try:
        _, err = proc.communicate(timeout=args.timeout)
    except subprocess.TimeoutExpired:
        timed_out = True
        proc.send_signal(signal.SIGTERM)
        try:
            _, err = proc.communicate(timeout=30)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            _, err = proc.communicate()
            proc.returncode = None
    stderr = err.decode("utf-8", "replace")
    verdict, why = classify(proc.returncode, stderr, out,
                            [str(scenario), scenario.name] + extra_names, timed_out)
    if verdict in FAILURES and args.keep:
        shutil.copy(scenario, Path(args.keep) / f"{verdict}_{index:05d}.toml")
    shutil.rmtree(case, ignore_errors=True)
    return verdict, f"m{index:05d} {name} {command} [{', '.join(kinds)}]: {why}"


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("rcdem")
    p.add_argument("source", type=Path)
    p.add_argument("--count", type=int, default=200)
    p.add_argument("--seed", type=int, default=None)
    p.add_argument("--jobs", type=int, default=os.cpu_count() or 1)
    p.add_argument("--timeout", type=float, default=20.0)
    p.add_argument("--memory-gib", type=float, default=4.0)
    p.add_argument("--keep", default="")
    p.add_argument("--verbose", action="store_true", help="a line per mutation")
    args = p.parse_args()
    args.memory = int(args.memory_gib * (1 << 30))
    # CI runs the same mutations every time unless RCDEM_FUZZ_SEED says otherwise.
    seed = args.seed if args.seed is not None else int(os.environ.get("RCDEM_FUZZ_SEED", 2026))
    print(f"seed {seed} (--seed to repeat), {args.count} mutations, {args.jobs} jobs")
    base_list = bases(args.source)
    if args.keep:
        Path(args.keep).mkdir(parents=True, exist_ok=True)
    work = Path(tempfile.mkdtemp(prefix="rcdem_fuzz_"))
    counts = collections.Counter()
    try:
        with ThreadPoolExecutor(args.jobs) as pool:
            rngs = [random.Random(seed * 1_000_003 + i) for i in range(args.count)]
            futures = [pool.submit(run_one, os.path.abspath(args.rcdem), work, i, rngs[i],
                                   base_list, args) for i in range(args.count)]
            for f in futures:
                verdict, line = f.result()
                counts[verdict] += 1
                if verdict in FAILURES or args.verbose:
                    print(f"{verdict} {line}", flush=True)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    for k in ("ok-exit-0", "ok-refused", "ok-interrupted") + FAILURES:
        print(f"{k:15s} {counts[k]}")
    failed = sum(counts[k] for k in FAILURES)
    print(f"{args.count - failed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
