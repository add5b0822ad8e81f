#!/usr/bin/env python3
"""run_bad_input.py RCDEM_BINARY BAD_INPUT_DIR

Runs `rcdem generate` on every malformed scenario BAD_INPUT_DIR/*.toml, and on a few bad command
lines that are not files (a scenario that does not exist or is a directory, an output path that
cannot be created or is not a directory), and checks that each is refused cleanly:

  * exit code 1 (not 0, not 3 = internal error, not a signal, not a timeout);
  * stdout empty;
  * stderr exactly one non-empty line, starting with 'rcdem: error: ';
  * every '# expect: TEXT' line at the top of the scenario file appears in that line;
  * the line names the scenario file (its path or basename), or for the output-path cases the
    output path;
  * no output directory holding files was left behind.

Prints 'ok   NAME: MESSAGE' or 'FAIL NAME: REASON' per case and finally 'N passed, M failed'.
Exits 1 if any case failed or fewer than 20 cases ran, 2 on bad usage.
"""
from __future__ import annotations

import dataclasses
import os
import resource
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path
from typing import Callable, Optional

TIMEOUT_S = 60
MIN_CASES = 20
# Address-space cap for rcdem, so that an input that makes it allocate without bound fails this
# test (as an internal error or a signal) instead of exhausting the machine.
MEMORY_LIMIT_BYTES = 8 << 30
PREFIX = "rcdem: error: "


@dataclasses.dataclass
class Case:
    name: str
    scenario: str  # the scenario argument as passed to rcdem
    output: str  # the -o argument
    expects: list[str]
    names: list[str]  # the message must contain at least one of these
    file_based: bool = True
    # The subcommand and any options after the scenario ('# command: run' in the file).
    command: list[str] = dataclasses.field(default_factory=lambda: ["generate"])
    # Extra check after the run; returns a failure reason or None.
    after: Optional[Callable[[], Optional[str]]] = None


def read_command(path: Path) -> list[str]:
    with open(path, "rb") as fh:
        for raw in fh:
            line = raw.decode("utf-8", errors="replace").strip()
            if line.startswith("# command:"):
                return line[len("# command:"):].split()
            if line and not line.startswith("#"):
                break
    return ["generate"]


def read_expects(path: Path) -> list[str]:
    expects = []
    with open(path, "rb") as fh:
        for raw in fh:
            line = raw.decode("utf-8", errors="replace").strip()
            if line.startswith("# expect:"):
                expects.append(line[len("# expect:"):].strip())
            elif line.startswith("#") or not line:
                continue
            else:
                break
    return expects


def limit_memory() -> None:
    try:
        resource.setrlimit(resource.RLIMIT_AS, (MEMORY_LIMIT_BYTES, MEMORY_LIMIT_BYTES))
    except (ValueError, OSError):
        pass


def dir_has_files(path: Path) -> bool:
    if not path.is_dir():
        return False
    return any(p.is_file() for p in path.rglob("*"))


def run_case(rcdem: str, case: Case, workdir: Path) -> tuple[bool, str]:
    env = dict(os.environ)
    env.setdefault("OMP_NUM_THREADS", "2")
    try:
        proc = subprocess.run(
            [rcdem, case.command[0], case.scenario, "-o", case.output, *case.command[1:]],
            cwd=workdir, env=env, stdin=subprocess.DEVNULL, capture_output=True,
            timeout=TIMEOUT_S, preexec_fn=limit_memory)
    except subprocess.TimeoutExpired:
        return False, f"no answer within {TIMEOUT_S} s (killed)"
    stderr = proc.stderr.decode("utf-8", errors="replace")
    stdout = proc.stdout.decode("utf-8", errors="replace")
    shown = stderr.strip().replace("\n", " | ")[:600]

    if proc.returncode < 0:
        return False, f"killed by signal {-proc.returncode}; stderr: {shown!r}"
    if proc.returncode != 1:
        what = {0: "accepted the input", 3: "internal error"}.get(proc.returncode, "unexpected")
        return False, f"exit code {proc.returncode} ({what}), expected 1; stderr: {shown!r}"
    if stdout:
        return False, f"stdout not empty: {stdout.strip()[:300]!r}; stderr: {shown!r}"
    lines = stderr.split("\n")
    if not stderr.endswith("\n") or len(lines) != 2 or "\r" in stderr:
        return False, f"stderr is not exactly one line: {stderr[:600]!r}"
    message = lines[0]
    if not message.startswith(PREFIX) or not message[len(PREFIX):].strip():
        return False, f"stderr does not start with {PREFIX!r} and a message: {message!r}"
    missing = [e for e in case.expects if e not in message]
    if missing:
        return False, f"message lacks {missing!r}: {message!r}"
    if case.names and not any(n in message for n in case.names):
        return False, f"message does not name {case.names[0]!r}: {message!r}"
    if case.file_based:
        out = Path(case.output)
        out = out if out.is_absolute() else workdir / out
        if dir_has_files(out):
            return False, f"output directory {case.output!r} was written: {message!r}"
    if case.after:
        reason = case.after()
        if reason:
            return False, f"{reason}: {message!r}"
    return True, message


def file_cases(bad_dir: Path, tmp: Path) -> list[Case]:
    cases = []
    for path in sorted(bad_dir.glob("*.toml")):
        out = tmp / f"{path.stem}.out" / "out"
        out.parent.mkdir()
        cases.append(Case(name=path.stem, scenario=str(path), output=str(out),
                          expects=read_expects(path),
                          # An error in a command-line option names the option, not the file.
                          names=[str(path), path.name] + [w.split("=")[0] for w in
                                                          read_command(path)[1:] if w.startswith("--")],
                          command=read_command(path)))
    return cases


def extra_cases(bad_dir: Path, tmp: Path) -> list[Case]:
    """Bad command lines that are not scenario files. `valid` is a scenario rcdem accepts."""
    valid = tmp / "valid_small.toml"
    valid.write_text('[specimen]\nshape = "box"\nsize = [0.05, 0.05, 0.05]\n')
    cases = []

    missing = tmp / "no_such_dir" / "missing.toml"
    cases.append(Case("x_scenario_does_not_exist", str(missing), str(tmp / "x1" / "out"),
                      ["cannot read scenario", "no such file"], [str(missing)]))

    a_dir = tmp / "scenario_is_a_directory.toml"
    a_dir.mkdir()
    cases.append(Case("x_scenario_is_a_directory", str(a_dir), str(tmp / "x2" / "out"),
                      ["cannot read scenario", "directory"], [str(a_dir)]))

    if os.geteuid() != 0:  # root reads a chmod 000 file anyway
        unreadable = tmp / "unreadable.toml"
        unreadable.write_text(valid.read_text())
        unreadable.chmod(0)
        cases.append(Case("x_scenario_unreadable", str(unreadable), str(tmp / "x3" / "out"),
                          ["cannot read scenario"], [str(unreadable)]))

    # Output paths. /proc refuses new directories even to root.
    proc_out = "/proc/rcdem_bad_input_out"
    cases.append(Case("x_output_under_proc", str(valid), proc_out,
                      ["output directory"], [proc_out], file_based=False,
                      after=lambda: "created it" if os.path.exists(proc_out) else None))

    a_file = tmp / "output_is_a_file"
    a_file.write_text("keep me\n")

    def file_untouched() -> Optional[str]:
        if not a_file.is_file() or a_file.read_text() != "keep me\n":
            return f"{a_file} was modified"
        return None

    cases.append(Case("x_output_is_a_regular_file", str(valid), str(a_file),
                      ["not a directory"], [str(a_file)], file_based=False, after=file_untouched))

    below_file = a_file / "out"
    cases.append(Case("x_output_below_a_regular_file", str(valid), str(below_file),
                      ["output directory"], [str(below_file)], file_based=False,
                      after=file_untouched))

    nonempty = tmp / "nonempty_out"
    nonempty.mkdir()
    (nonempty / "particles.vtu").write_text("old results\n")

    def old_results_kept() -> Optional[str]:
        files = sorted(p.name for p in nonempty.iterdir())
        if files != ["particles.vtu"] or (nonempty / "particles.vtu").read_text() != "old results\n":
            return f"the non-empty output directory was modified: {files}"
        return None

    cases.append(Case("x_output_not_empty_without_force", str(valid), str(nonempty),
                      ["not empty", "--force"], [str(nonempty)], file_based=False,
                      after=old_results_kept))

    cases += hostile_file_cases(tmp, valid)

    if os.geteuid() != 0:  # root writes into a read-only directory anyway
        readonly = tmp / "readonly_parent"
        readonly.mkdir()
        readonly.chmod(0o555)
        cases.append(Case("x_output_parent_read_only", str(valid), str(readonly / "out"),
                          ["output directory"], [str(readonly / "out")], file_based=False))
    return cases


def hostile_file_cases(tmp: Path, valid: Path) -> list[Case]:
    """Files that crashed, hung or exhausted rcdem before it refused them (issue 28, 1-4)."""
    body = valid.read_text()
    cases = []

    def scenario(name: str, text: str) -> Path:
        path = tmp / f"{name}.toml"
        path.write_text(text)
        return path

    levels = 50_000  # segfaulted in the TOML parser (stack overflow)
    deep_key = scenario("deep_dotted_key", body + ".".join(["a"] * levels) + " = 1\n")
    deep_header = scenario("deep_header", body + "[" + ".".join(["a"] * levels) + "]\n")
    for path in (deep_key, deep_header):
        cases.append(Case(f"x_{path.stem}", str(path), str(tmp / path.stem / "out"),
                          ["nested more than"], [str(path)]))

    fifo = tmp / "fifo.toml"
    os.mkfifo(fifo)  # open() blocked forever
    cases.append(Case("x_scenario_is_a_fifo", str(fifo), str(tmp / "fifo_out" / "out"),
                      ["not a regular file"], [str(fifo)]))
    for name, target, expect in [("fifo", "fifo.toml", "not a regular file"),
                                 ("dev_zero", "/dev/zero", "not a regular file"),  # bad_alloc
                                 ("dev_urandom", "/dev/urandom", "not a regular file"),
                                 ("directory", ".", "directory"),  # read as an empty fragment
                                 ("empty_name", "", "empty file name")]:
        path = scenario(f"include_{name}", f'include = "{target}"\n' + body)
        cases.append(Case(f"x_include_{name}", str(path), str(tmp / path.stem / "out"),
                          ["key 'include'", expect], [str(path)]))

    huge = scenario("oversized", body + ("# padding " * 100 + "\n") * 5000)  # 5 MB
    cases.append(Case("x_scenario_oversized", str(huge), str(tmp / "huge_out" / "out"),
                      ["bytes"], [str(huge)]))
    return cases


def main(argv: list[str]) -> int:
    if len(argv) != 3:
        print(__doc__.strip().splitlines()[0], file=sys.stderr)
        return 2
    rcdem = os.path.abspath(argv[1])
    bad_dir = Path(argv[2]).resolve()
    if os.path.isdir(rcdem):
        rcdem = os.path.join(rcdem, "rcdem")
    if not os.access(rcdem, os.X_OK) or not bad_dir.is_dir():
        print(f"run_bad_input: need an rcdem executable and a directory, got {argv[1:]}",
              file=sys.stderr)
        return 2

    tmp = Path(tempfile.mkdtemp(prefix="rcdem_bad_input_"))
    passed = failed = 0
    try:
        cases = file_cases(bad_dir, tmp) + extra_cases(bad_dir, tmp)
        for case in cases:
            if case.file_based and not case.expects and not case.name.startswith("x_"):
                ok, text = False, "the file has no '# expect:' line"
            else:
                ok, text = run_case(rcdem, case, tmp)
            if ok:
                passed += 1
                print(f"ok   {case.name}: {text}")
            else:
                failed += 1
                print(f"FAIL {case.name}: {text}")
            sys.stdout.flush()
    finally:
        for p in tmp.rglob("*"):  # undo chmods so that the tree can be removed
            try:
                if p.is_dir() and not p.is_symlink():
                    p.chmod(0o755)
            except OSError:
                pass
        shutil.rmtree(tmp, ignore_errors=True)

    print(f"{passed} passed, {failed} failed")
    if passed + failed < MIN_CASES:
        print(f"run_bad_input: only {passed + failed} cases ran, at least {MIN_CASES} required",
              file=sys.stderr)
        return 1
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
