#!/usr/bin/python3
"""A seeded fuzzer of what lies around a scenario (issue 44): output directories, checkpoints,
signals and studies, the second generator beside fuzz_scenarios.py.

From three artefacts made once (a finished run, a run interrupted after two checkpoints, a
finished study of two cases), each case takes a fresh copy, changes it in one or two random ways
and runs rcdem on it:

  force       foreign entries (files, directories, symlinks, FIFOs, names with quotes, spaces,
              newlines or `$()`) put in a run directory, its mark removed, or a half-done
              replacement (.rcdem-replaced with part of its journal's entries moved) left in it;
              then `run --force` into it;
  checkpoint  checkpoints truncated, bytes flipped, swapped, deleted, replaced by a FIFO, a
              directory, a symlink to /dev/zero, an empty or a huge sparse file; then `--resume`;
  signal      a run sent SIGINT, SIGTERM or SIGHUP (once, or twice in quick succession) at a random
              moment, then resumed until it finishes;
  study       a finished case's history.csv cut or deleted, summary.json emptied or given a string
              for a number, its manifest deleted, its scenario edited, or a file of the user's put
              in a case; then the same study again.

Each outcome is classified:

  ok          exit 0 with a complete result (summary.json and history.csv to its last step), or
              exit 1 with one line 'rcdem: error: ...';
  LOSS        a file rcdem did not write was removed or changed;
  STALE       exit 0 while a result is missing, damaged or differs from the uninterrupted run's
              (a resumed run's history.csv must equal it byte for byte);
  CRASH       killed by a signal it did not document, or exit 3 (internal error);
  HANG        no exit within --timeout s;
  BAD-MESSAGE any other exit, or an error that is not one line.

Prints a line per case with --verbose (else per failure) and a table of counts; exits 1 if any
failure. The seed is --seed, or RCDEM_FUZZ_SEED; --budget bounds the wall time (cases not started
by then are skipped, and said so).

usage: fuzz_directories.py RCDEM SOURCE_DIR [--count N] [--seed S] [--timeout T] [--budget B]
                           [--verbose]
"""
from __future__ import annotations

import argparse
import collections
import glob
import hashlib
import json
import os
import random
import shutil
import signal
import subprocess
import sys
import tempfile
import time

FAILURES = ("LOSS", "STALE", "CRASH", "HANG", "BAD-MESSAGE")
DOCUMENTED_EXITS = {0, 1, 128 + signal.SIGINT, 128 + signal.SIGTERM, 128 + signal.SIGHUP}
ODD_NAMES = ["notes.txt", "O'Brien.csv", "a b", "$(touch PWNED)", "new\nline", "data", ".hidden",
             "history.csv.bak", "`id`", "summary.json~"]


class Fuzzer:
    def __init__(self, rcdem, source, tmp, timeout, rng, verbose):
        self.rcdem, self.source, self.tmp = rcdem, source, tmp
        self.timeout, self.rng, self.verbose = timeout, rng, verbose
        self.counts = collections.Counter()
        self.failures = []
        text = open(os.path.join(source, "tests/regression/small_run.toml")).read()
        self.scenario = os.path.join(tmp, "base.toml")
        open(self.scenario, "w").write(text)

    # ---- running rcdem ----
    def run(self, args, cwd=None):
        """(returncode or None on a hang, stderr)."""
        try:
            r = subprocess.run([self.rcdem, "-q"] + args, capture_output=True, text=True,
                               timeout=self.timeout, cwd=cwd or self.tmp)
            return r.returncode, r.stderr
        except subprocess.TimeoutExpired:
            return None, ""

    def outcome(self, code, err):
        """The class of an exit that needs no further check beyond 'ok'."""
        if code is None:
            return "HANG"
        if code < 0 or code == 3:
            return "CRASH"
        lines = [x for x in err.strip().splitlines() if not x.startswith("rcdem: warning:")]
        if code == 1 and not (len(lines) == 1 and lines[0].startswith("rcdem: error: ")):
            return "BAD-MESSAGE"
        if code not in DOCUMENTED_EXITS:
            return "BAD-MESSAGE"
        return "ok"

    def record(self, kind, what, cls, detail=""):
        self.counts[(kind, cls)] += 1
        if cls != "ok":
            self.failures.append(f"{cls} {kind}: {what}: {detail}")
        if cls != "ok" or self.verbose:
            print(f"{cls:11s} {kind}: {what} {detail[:200]!r}")

    # ---- the artefacts ----
    def prepare(self):
        self.finished = os.path.join(self.tmp, "finished")
        code, err = self.run(["run", self.scenario, "-o", self.finished])
        assert code == 0, err
        self.reference = open(os.path.join(self.finished, "history.csv"), "rb").read()
        self.interrupted = os.path.join(self.tmp, "interrupted")
        p = subprocess.Popen([self.rcdem, "-q", "run", self.scenario, "-o", self.interrupted,
                              "--checkpoint-every", "100"], stdout=subprocess.DEVNULL,
                             stderr=subprocess.DEVNULL)
        while p.poll() is None and len(self.checkpoints(self.interrupted)) < 2:
            time.sleep(0.005)
        p.send_signal(signal.SIGINT)
        p.wait()
        assert self.checkpoints(self.interrupted), "no checkpoint to fuzz"
        self.scenarios = os.path.join(self.tmp, "study_scenarios")
        os.makedirs(self.scenarios)
        for name, steps in (("a", 300), ("b", 400)):
            open(os.path.join(self.scenarios, name + ".toml"), "w").write(
                open(self.scenario).read().replace("steps = 3000", f"steps = {steps}"))
        self.study_dir = os.path.join(self.tmp, "study")
        code, err = self.run(["study", "generic", "--scenarios", self.scenarios, "-o",
                              self.study_dir])
        assert code == 0, err

    @staticmethod
    def checkpoints(d):
        return sorted(glob.glob(os.path.join(d, "checkpoint_*.h5"))) if os.path.isdir(d) else []

    def fresh(self, src, k):
        dst = os.path.join(self.tmp, f"case{k}")
        shutil.rmtree(dst, ignore_errors=True)
        shutil.copytree(src, dst, symlinks=True)
        return dst

    def complete(self, d):
        """Whether d holds a finished run equal to the uninterrupted one."""
        try:
            s = json.load(open(os.path.join(d, "summary.json")))
            return (isinstance(s, dict) and open(os.path.join(d, "history.csv"), "rb").read()
                    == self.reference)
        except (OSError, ValueError):
            return False

    # ---- the four kinds ----
    def foreign(self, d):
        """Puts one of the user's entries into d; returns its path."""
        name = self.rng.choice(ODD_NAMES)
        path = os.path.join(d, name)
        while os.path.lexists(path):
            path += "_"
        kind = self.rng.choice(["file", "dir", "symlink", "fifo"])
        if kind == "file":
            open(path, "w").write("the user's " + str(self.rng.random()))
        elif kind == "dir":
            os.makedirs(path)
            open(os.path.join(path, "inside.txt"), "w").write("kept")
        elif kind == "symlink":
            target = os.path.join(self.tmp, "symlink_target.txt")
            open(target, "w").write("target")
            os.symlink(target, path)
        else:
            os.mkfifo(path)
        return path

    def case_force(self, k):
        d = self.fresh(self.finished, k)
        ops, foreign = [], []
        for _ in range(self.rng.randint(1, 2)):
            op = self.rng.choice(["foreign", "unmark", "half-replaced", "foreign"])
            ops.append(op)
            if op == "foreign":
                foreign.append(self.foreign(d))
            elif op == "unmark" and os.path.exists(os.path.join(d, ".rcdem-outputs")):
                os.remove(os.path.join(d, ".rcdem-outputs"))
            elif op == "half-replaced" and not os.path.exists(os.path.join(d, ".rcdem-replaced")):
                aside = os.path.join(d, ".rcdem-replaced")
                names = sorted(n for n in os.listdir(d) if not n.startswith(".")
                               and n not in [os.path.basename(f) for f in foreign])
                os.makedirs(aside)
                open(os.path.join(aside, ".rcdem-journal"), "w").write(
                    "".join(n + "\n" for n in names))
                for n in self.rng.sample(names, self.rng.randint(0, len(names))):
                    os.rename(os.path.join(d, n), os.path.join(aside, n))
        before = {f: self.snapshot(f) for f in foreign}
        code, err = self.run(["run", self.scenario, "-o", d, "--force"])
        cls = self.outcome(code, err)
        lost = [f for f in foreign if self.snapshot(f) != before[f]]
        if lost:
            cls = "LOSS"
        elif cls == "ok" and code == 0 and (foreign or not self.complete(d)):
            cls = "STALE"
        self.record("force", "+".join(ops), cls, f"exit {code}: {err.strip()[-160:]}")

    def cut(self, path):
        """The file cut at a random length shorter than its own."""
        os.truncate(path, self.rng.randrange(os.path.getsize(path)))

    @staticmethod
    def snapshot(path):
        if os.path.islink(path):
            return ("link", os.readlink(path))
        if os.path.isdir(path):
            return ("dir", sorted(os.listdir(path)))
        if not os.path.exists(path):
            return None
        if not os.path.isfile(path):
            return ("special",)
        return ("file", hashlib.sha256(open(path, "rb").read()).hexdigest())

    def damage_checkpoint(self, d, path):
        op = self.rng.choice(["truncate", "flip", "fifo", "dir", "devzero", "empty", "sparse",
                              "delete", "swap"])
        size = os.path.getsize(path)
        if op == "truncate":
            self.cut(path)
        elif op == "flip":
            with open(path, "r+b") as f:
                for _ in range(self.rng.randint(1, 4)):
                    f.seek(self.rng.randrange(size))
                    b = f.read(1)
                    f.seek(-1, 1)
                    f.write(bytes([b[0] ^ (1 << self.rng.randrange(8))]))
        elif op in ("fifo", "dir", "devzero", "empty", "sparse", "delete"):
            os.remove(path)
            if op == "fifo":
                os.mkfifo(path)
            elif op == "dir":
                os.makedirs(path)
            elif op == "devzero":
                os.symlink("/dev/zero", path)
            elif op == "empty":
                open(path, "w").close()
            elif op == "sparse":
                with open(path, "wb") as f:
                    f.truncate(1 << self.rng.choice([30, 36, 40]))
        elif op == "swap":
            others = [c for c in self.checkpoints(d) if c != path]
            if others:
                other = self.rng.choice(others)
                os.rename(path, path + ".x")
                os.rename(other, path)
                os.rename(path + ".x", other)
        return op

    def case_checkpoint(self, k):
        d = self.fresh(self.interrupted, k)
        ops = []
        for path in self.rng.sample(self.checkpoints(d),
                                    self.rng.randint(1, len(self.checkpoints(d)))):
            if os.path.lexists(path):
                ops.append(self.damage_checkpoint(d, path))
        if self.rng.random() < 0.2:  # a damaged "newer" checkpoint
            extra = os.path.join(d, "checkpoint_999999999999.h5")
            shutil.copy(self.checkpoints(self.interrupted)[0], extra)
            ops.append("newer-" + self.damage_checkpoint(d, extra))
        code, err = self.run(["run", "--resume", d])
        cls = self.outcome(code, err)
        if cls == "ok" and code == 0 and not self.complete(d):
            cls = "STALE"
        if cls == "ok" and code not in (0, 1):
            cls = "BAD-MESSAGE"
        self.record("checkpoint", "+".join(ops), cls, f"exit {code}: {err.strip()[-160:]}")

    def case_signal(self, k):
        d = os.path.join(self.tmp, f"case{k}")
        shutil.rmtree(d, ignore_errors=True)
        sig = self.rng.choice([signal.SIGINT, signal.SIGTERM, signal.SIGHUP])
        delay, twice = self.rng.uniform(0.0, 1.5), self.rng.random() < 0.3
        p = subprocess.Popen([self.rcdem, "-q", "run", self.scenario, "-o", d,
                              "--checkpoint-every", str(self.rng.choice([0, 50, 300]))],
                             stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        time.sleep(delay)
        if p.poll() is None:
            p.send_signal(sig)
            if twice:
                time.sleep(0.002)
                p.send_signal(sig)
        try:
            _, err = p.communicate(timeout=self.timeout)
            code = p.returncode
        except subprocess.TimeoutExpired:
            p.kill()
            self.record("signal", f"{sig.name} after {delay:.2f} s", "HANG")
            return
        what = f"{sig.name}{' twice' if twice else ''} after {delay:.2f} s"
        cls = self.outcome(code, err)
        resumes = 0
        while cls == "ok" and code != 0 and self.checkpoints(d) and resumes < 3:
            resumes += 1
            code, err = self.run(["run", "--resume", d])
            cls = self.outcome(code, err)
        if cls == "ok" and code == 0 and not self.complete(d):
            cls = "STALE"
        if cls == "ok" and code not in (0, 1, 128 + sig):
            cls = "BAD-MESSAGE"
        self.record("signal", what + f", {resumes} resume(s)", cls, f"exit {code}: {err[-160:]}")

    def case_study(self, k):
        d = self.fresh(self.study_dir, k)
        case = os.path.join(d, "cases", self.rng.choice(["a", "b"]))
        op = self.rng.choice(["cut-history", "delete-history", "empty-summary", "string-summary",
                              "delete-manifest", "foreign-file", "edit-scenario", "cut-summary"])
        scenarios = self.scenarios
        if op == "cut-history":
            self.cut(os.path.join(case, "history.csv"))
        elif op == "delete-history":
            os.remove(os.path.join(case, "history.csv"))
        elif op == "empty-summary":
            open(os.path.join(case, "summary.json"), "w").write(self.rng.choice(["{}", "[]", ""]))
        elif op == "string-summary":
            s = json.load(open(os.path.join(case, "summary.json")))
            s[self.rng.choice(["peak_load_N", "steps", "seconds"])] = "12"
            json.dump(s, open(os.path.join(case, "summary.json"), "w"))
        elif op == "cut-summary":
            self.cut(os.path.join(case, "summary.json"))
        elif op == "delete-manifest":
            os.remove(os.path.join(case, "manifest.json"))
        elif op == "foreign-file":
            foreign = self.foreign(case)
            kept = self.snapshot(foreign)
        elif op == "edit-scenario":
            scenarios = os.path.join(self.tmp, f"scenarios{k}")
            shutil.rmtree(scenarios, ignore_errors=True)
            shutil.copytree(self.scenarios, scenarios)
            name = os.path.basename(case) + ".toml"
            text = open(os.path.join(scenarios, name)).read()
            open(os.path.join(scenarios, name), "w").write(text.replace("seed = 3", "seed = 4"))
        code, err = self.run(["study", "generic", "--scenarios", scenarios, "-o", d])
        cls = self.outcome(code, err)
        if op == "foreign-file" and self.snapshot(foreign) != kept:
            cls = "LOSS"
        if cls == "ok" and code == 0:
            for c in ("a", "b"):
                cd = os.path.join(d, "cases", c)
                try:
                    s = json.load(open(os.path.join(cd, "summary.json")))
                    rows = open(os.path.join(cd, "history.csv")).read().splitlines()
                    if int(rows[-1].split(",")[0]) != s["steps"]:
                        cls = "STALE"
                except (OSError, ValueError, KeyError, TypeError, IndexError):
                    cls = "STALE"
            before = open(os.path.join(self.study_dir, "cases", os.path.basename(case),
                                       "history.csv"), "rb").read()
            if op == "edit-scenario" and open(os.path.join(case, "history.csv"),
                                              "rb").read() == before:
                cls = "STALE"  # the edited case was not run again
        self.record("study", op, cls, f"exit {code}: {err.strip()[-160:]}")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("rcdem")
    ap.add_argument("source")
    ap.add_argument("--count", type=int, default=60)
    ap.add_argument("--seed", type=int, default=int(os.environ.get("RCDEM_FUZZ_SEED", 44)))
    ap.add_argument("--timeout", type=float, default=120)
    ap.add_argument("--budget", type=float, default=600)
    ap.add_argument("--verbose", action="store_true")
    a = ap.parse_args()
    rng = random.Random(a.seed)
    t0 = time.time()
    print(f"seed {a.seed} (--seed or RCDEM_FUZZ_SEED for others), {a.count} cases")
    with tempfile.TemporaryDirectory() as tmp:
        f = Fuzzer(os.path.abspath(a.rcdem), os.path.abspath(a.source), tmp, a.timeout, rng,
                   a.verbose)
        f.prepare()
        kinds = [f.case_force, f.case_checkpoint, f.case_signal, f.case_study]
        skipped = 0
        for k in range(a.count):
            if time.time() - t0 > a.budget:
                skipped = a.count - k
                break
            kinds[k % len(kinds)](k)
            shutil.rmtree(os.path.join(tmp, f"case{k}"), ignore_errors=True)
        if os.path.exists(os.path.join(tmp, "PWNED")):
            f.failures.append("a name was run as shell code (PWNED exists)")
    print("\nkind        class        count")
    for (kind, cls), n in sorted(f.counts.items()):
        print(f"{kind:11s} {cls:12s} {n}")
    if skipped:
        print(f"{skipped} cases not started: the --budget of {a.budget:.0f} s was spent")
    ran = sum(f.counts.values())
    print(f"{ran - len(f.failures)} passed, {len(f.failures)} failed")
    sys.exit(1 if f.failures or ran == 0 else 0)


if __name__ == "__main__":
    main()
