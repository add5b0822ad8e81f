#!/usr/bin/python3
"""End-to-end check of checkpoints and resuming (issue 6, docs/checkpoint.md) with `rcdem run`
on tests/regression/small_run.toml (4,000 steps here):

  * a run killed with SIGKILL at a random moment after its first checkpoint, then
    `rcdem run --resume DIR`, ends with the same history.csv, broken_points.csv, final snapshots
    and .pvd series (bytewise) and summary.json (every field but the wall-clock ones) as an
    uninterrupted run; its manifest tells both sessions;
  * SIGINT (after two periodic checkpoints): exit code 130 within 2 s, a message with
    "--resume", a checkpoint of the step it stopped at, the last two kept, the file reads as
    docs/checkpoint.md describes it (h5py; header, sections, CRC-32 checked here with zlib); resumed
    (at 2 threads) it ends as the uninterrupted run;
  * SIGTERM twice within 3 ms (as GNU timeout may deliver it): one request, exit 143 and a
    checkpoint, in each of 3 runs;
  * the newest checkpoint corrupted: rejected with a message naming it and the reason, the
    previous one used, the same result; both corrupted: a clear error;
  * a full disk (RLIMIT_FSIZE: writes fail with EFBIG) during a resumed run: a clear error that
    says how to continue, the earlier checkpoints intact, and the run then completes;
  * 1 and 2 threads give bitwise the same outputs on a 100 mm cube (15,758 contacts, 2,517
    bodies: the parallel loops run in parallel), and so does --threads 1 against the default
    (auto, the count following the free cores); a bad --threads is one line naming it.

usage: check_resume.py RCDEM_BINARY SOURCE_DIR
"""
import json
import os
import random
import re
import resource
import shutil
import signal
import struct
import subprocess
import sys
import tempfile
import time
import zlib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checklist import Checklist  # noqa: E402
from checkpoint_image import binary_image, documented_version  # noqa: E402

rcdem, source = sys.argv[1], sys.argv[2]
checks = Checklist()
check = checks.check
# What depends on the machine's load: wall times, and the thread counts a run followed (--threads
# auto changes the count with the free cores; the results do not change).
WALL_CLOCK = {"seconds", "loop_seconds", "steps_per_second", "step_seconds", "threads"}
CKPT = re.compile(r"^checkpoint_(\d{12})\.h5$")
seed = int(os.environ.get("RCDEM_TEST_SEED", random.randrange(1 << 30)))
rng = random.Random(seed)
print(f"random seed {seed} (set RCDEM_TEST_SEED to repeat)")


def env(threads=1):
    e = dict(os.environ)
    e["OMP_NUM_THREADS"] = str(threads)
    return e


def run(args, threads=1, **kw):
    return subprocess.run([rcdem] + args, capture_output=True, text=True, timeout=300,
                          env=env(threads), **kw)


def start(args, threads=1, **kw):
    return subprocess.Popen([rcdem] + args, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True, env=env(threads), **kw)


def checkpoints(d):
    if not os.path.isdir(d):
        return []
    return sorted((int(m.group(1)), os.path.join(d, f))
                  for f in os.listdir(d) if (m := CKPT.match(f)))


def wait_for(cond, proc, timeout=120):
    t0 = time.time()
    while time.time() - t0 < timeout:
        if cond():
            return True
        if proc.poll() is not None:
            return False
        time.sleep(0.005)
    return False


def read_bytes(p):
    with open(p, "rb") as f:
        return f.read()


def summary(d):
    s = json.load(open(os.path.join(d, "summary.json")))
    return {k: v for k, v in s.items() if k not in WALL_CLOCK}


def outputs(d):
    """Every result file but the wall-clock summary fields, manifest and initial files."""
    out = {f: read_bytes(os.path.join(d, f))
           for f in ("history.csv", "broken_points.csv", "particles.pvd", "facets.pvd", "bars.pvd")}
    snaps = os.path.join(d, "snapshots")
    for f in sorted(os.listdir(snaps)):
        out["snapshots/" + f] = read_bytes(os.path.join(snaps, f))
    out["summary.json"] = summary(d)
    return out


def same_as(ref, d, what):
    a, b = outputs(ref), outputs(d)
    diff = [k for k in sorted(set(a) | set(b)) if a.get(k) != b.get(k)]
    check(not diff, f"{what}: identical outputs ({len(a)} files{'; differ: ' + ', '.join(diff[:5]) if diff else ''})")


def parse_checkpoint(path):
    """The layout of docs/checkpoint.md, read independently of rcdem (h5py and the byte layout
    of the image)."""
    data = binary_image(path)
    h = {"magic": data[:8]}
    h["version"], h["bom"] = struct.unpack_from("<II", data, 8)
    h["size"], h["step"], h["time"] = struct.unpack_from("<Qqd", data, 16)
    h["scenario_hash"], h["fingerprint"] = struct.unpack_from("<QQ", data, 40)
    nsec, wlen = struct.unpack_from("<II", data, 56)
    h["writer"] = data[64:64 + wlen].decode()
    at = 64 + wlen
    sections = {}
    for _ in range(nsec):
        (nlen,) = struct.unpack_from("<I", data, at)
        name = data[at + 4:at + 4 + nlen].decode()
        at += 4 + nlen
        kind, width, count = struct.unpack_from("<IIQ", data, at)
        at += 16
        sections[name] = (kind, width, count, at)
        at += 8 * width * count if kind == 1 else count
    (crc,) = struct.unpack_from("<I", data, at)
    h["crc_ok"] = at + 4 == len(data) and zlib.crc32(data[:at]) == crc
    h["sections"] = sections
    h["data"] = data
    return h


tmp = tempfile.mkdtemp(prefix="rcdem_resume_")
try:
    text = open(os.path.join(source, "tests", "regression", "small_run.toml")).read()
    scenario = os.path.join(tmp, "resume_run.toml")
    open(scenario, "w").write(text.replace("steps = 3000", "steps = 4000")
                              .replace("history_rows = 100", "history_rows = 200"))

    # --- The uninterrupted run. -------------------------------------------------------------
    ref = os.path.join(tmp, "ref")
    t0 = time.time()
    r = run(["run", scenario, "-o", ref])
    t_ref = time.time() - t0
    check(r.returncode == 0, f"uninterrupted run exits 0 in {t_ref:.1f} s"
          + ("" if r.returncode == 0 else f" ({r.stderr.strip()[-300:]})"))
    m = json.load(open(os.path.join(ref, "manifest.json")))
    check(m["exit_state"] == "finished" and m["steps"] == 4000 and len(m["sessions"]) == 1
          and m["rcdem_version"] and m["git_hash"] and m["threads"] == 1 and m["start_time"]
          and m["end_time"] and m["wall_seconds"] > 0 and m["inputs"][0]["fnv1a64"],
          "manifest.json: finished, 4000 steps, version, git hash, threads, times, inputs")
    check(not checkpoints(ref) and not os.path.exists(os.path.join(ref, "run.lock")),
          "a finished run leaves no checkpoint and no lock")
    r = run(["run", scenario, "-o", ref])
    check(r.returncode == 1 and "--force" in r.stderr, "results are not overwritten without --force")

    # --- SIGKILL at a random moment after the first checkpoint, then --resume. ---------------
    killed = os.path.join(tmp, "killed")
    for attempt in range(4):
        shutil.rmtree(killed, ignore_errors=True)
        p = start(["run", scenario, "-o", killed, "--checkpoint-every", "300"])
        got = wait_for(lambda: checkpoints(killed), p)
        delay = rng.uniform(0.0, 0.5 * t_ref) / (attempt + 1)
        time.sleep(delay)
        p.send_signal(signal.SIGKILL)
        p.communicate()
        if got and p.returncode == -signal.SIGKILL and not os.path.exists(
                os.path.join(killed, "summary.json")):
            break
        print(f"(attempt {attempt + 1}: the run ended before the kill; again, sooner)")
    done = checkpoints(killed)
    check(p.returncode == -signal.SIGKILL and done,
          f"killed with SIGKILL {delay:.2f} s after its first checkpoint; checkpoints of steps "
          f"{[s for s, _ in done]}")
    r = run(["run", "--resume", killed])
    last = done[-1][0] if done else -1
    check(r.returncode == 0 and f"resuming from {os.path.join(killed, f'checkpoint_{last:012d}.h5')}"
          in r.stderr, f"--resume continues from the newest checkpoint, step {last} "
          + ("" if r.returncode == 0 else f"({r.stderr.strip()[-300:]})"))
    same_as(ref, killed, "SIGKILL + --resume vs uninterrupted")
    m = json.load(open(os.path.join(killed, "manifest.json")))
    states = [s["exit_state"] for s in m["sessions"]]
    check(states == ["killed", "finished"] and m["sessions"][1]["resumed_from"]["step"] == last
          and m["exit_state"] == "finished",
          f"manifest: sessions {states}, the second resumed from step {last}")
    # Issue 28: a --resume without --checkpoint-every keeps the run's own interval.
    kept = [s.get("checkpoint_every") for s in m["sessions"]]
    check(kept == ["300", "300"] and m.get("checkpoint_every") == "300",
          f"--checkpoint-every 300 kept by the resumed session: {kept}")
    check(not [f for f in os.listdir(killed) if ".tmp." in f] and not checkpoints(killed),
          "no temporary file or checkpoint left after the resumed run")
    r = run(["run", "--resume", killed])
    check(r.returncode == 1 and "has finished" in r.stderr,
          f"resuming a finished run is refused ({r.stderr.strip()})")

    # --- SIGINT: a checkpoint, exit 130 within 2 s, a message saying how to resume. ----------
    # Checkpoints every 300 steps, SIGINT once two exist: a third is written, two are kept.
    intr = os.path.join(tmp, "interrupted")
    for attempt in range(4):
        shutil.rmtree(intr, ignore_errors=True)
        p = start(["run", scenario, "-o", intr, "--checkpoint-every", "300"])
        wait_for(lambda: len(checkpoints(intr)) >= 2, p)
        time.sleep(rng.uniform(0.0, 0.3 * t_ref) / (attempt + 1))
        t_sig = time.time()
        p.send_signal(signal.SIGINT)
        _, err = p.communicate()
        t_exit = time.time() - t_sig
        if p.returncode == 130 or not os.path.exists(os.path.join(intr, "summary.json")):
            break
        print(f"(attempt {attempt + 1}: the run ended before SIGINT; again, sooner)")
    check(p.returncode == 130, f"SIGINT: exit code 130 (got {p.returncode})"
          + ("" if p.returncode == 130 else f" ({err.strip()[-300:]})"))
    check(t_exit < 2.0, f"SIGINT: exits {t_exit:.3f} s after the signal (< 2 s)")
    check(f"rcdem run --resume {intr}" in err, f"the message says how to resume: {err.strip().splitlines()[-1]!r}")
    ck = checkpoints(intr)
    at_step = re.search(r"interrupted by SIGINT at step (\d+)", err)
    at_step = int(at_step.group(1)) if at_step else -1
    check(ck and ck[-1][0] == at_step, f"SIGINT wrote a checkpoint of step {at_step}")
    check(len(ck) == 2, f"the last two checkpoints are kept ({[s for s, _ in ck]})")
    m = json.load(open(os.path.join(intr, "manifest.json")))
    check(m["exit_state"] == "interrupted" and m["sessions"][0]["signal"] == "SIGINT"
          and m["last_checkpoint"]["step"] == at_step,
          "manifest: interrupted by SIGINT, its last checkpoint")
    if ck:
        h = parse_checkpoint(ck[-1][1])
        documented = documented_version(source)
        check(h["magic"] == b"RCDEMCKP" and h["version"] == documented
              and h["bom"] == 0x01020304 and h["size"] == len(h["data"])
              and h["step"] == at_step and h["crc_ok"] and h["writer"].startswith("rcdem "),
              f"the checkpoint reads as documented (h5py, the image of format {h['version']}, "
              f"docs/checkpoint.md's {documented}: "
              f"{len(h['data'])} bytes, {len(h['sections'])} sections, CRC-32 checked by zlib)")
        need = {"bodies": 22, "bodies.step": 3, "contacts": 17, "contacts.points": 9,
                "interface.0": 17, "interface.0.points": 9, "nodes": 35, "plates": 8,
                "plate_contacts": 21, "pulled_bars": 7, "solver": 11,
                "history": len(open(os.path.join(ref, "history.csv")).readline().split(",")),
                "cracks": 7, "run": 7, "snapshots.particles": 1}
        bad = [n for n, w in need.items()
               if n not in h["sections"] or h["sections"][n][1] != w]
        check(not bad, f"documented sections and widths present ({bad or 'all'})")
        kind, width, count, at = h["sections"]["solver"]
        t, steps = struct.unpack_from("<dq", h["data"], at)
        check(t == h["time"] and steps == h["step"], "section 'solver' holds the header's time and step")
    r = run(["run", "--resume", intr], threads=2)
    check(r.returncode == 0, "the interrupted run resumes at 2 threads"
          + ("" if r.returncode == 0 else f" ({r.stderr.strip()[-300:]})"))
    same_as(ref, intr, "SIGINT + --resume (2 threads) vs uninterrupted (1 thread)")

    # --- SIGTERM twice, milliseconds apart (GNU timeout signals the run, then its process group):
    # one request, a checkpoint and exit 143 every time; a binary that takes the second copy for
    # the user insisting died without a checkpoint in 4 of 6 such runs. -------------------------
    twice = os.path.join(tmp, "term_twice")
    results = []
    for _ in range(3):
        shutil.rmtree(twice, ignore_errors=True)
        p = start(["run", scenario, "-o", twice, "--checkpoint-every", "300"])
        wait_for(lambda: len(checkpoints(twice)) >= 1, p)
        p.send_signal(signal.SIGTERM)
        time.sleep(0.003)
        if p.poll() is None:
            p.send_signal(signal.SIGTERM)
        _, err = p.communicate()
        at_step = re.search(r"interrupted by SIGTERM at step (\d+)", err)
        ck = checkpoints(twice)
        results.append((p.returncode, bool(at_step and ck and ck[-1][0] == int(at_step.group(1)))))
    check(all(r == (143, True) for r in results),
          f"SIGTERM twice within 3 ms: exit 143 with a checkpoint of the step it stopped at, "
          f"3 runs of 3 ({results})")

    # --- A corrupted newest checkpoint: the previous one is used. -----------------------------
    corrupt = os.path.join(tmp, "corrupt")
    for attempt in range(4):
        shutil.rmtree(corrupt, ignore_errors=True)
        p = start(["run", scenario, "-o", corrupt, "--checkpoint-every", "500"])
        got = wait_for(lambda: len(checkpoints(corrupt)) >= 2, p)
        p.send_signal(signal.SIGINT)  # between steps: never while old checkpoints are pruned
        p.communicate()
        if got and p.returncode == 130:
            break
    ck = checkpoints(corrupt)
    check(len(ck) == 2, f"two checkpoints to choose from ({[s for s, _ in ck]})")
    (old_step, old), (new_step, new) = ck
    old_bytes = read_bytes(old)
    saved = read_bytes(new)
    data = bytearray(saved)
    data[len(data) // 2] ^= 0x04
    open(new, "wb").write(data)
    r = run(["run", "--resume", corrupt])
    check(r.returncode == 0, "resumes past a corrupted checkpoint"
          + ("" if r.returncode == 0 else f" ({r.stderr.strip()[-300:]})"))
    check(f"checkpoint '{new}' rejected: checksum mismatch" in r.stderr,
          "the corrupted one is rejected, named, with the reason: "
          + next((l for l in r.stderr.splitlines() if "rejected" in l), "(no message)"))
    check(f"resuming from {old} (step {old_step}" in r.stderr, f"the previous one (step {old_step}) is used")
    same_as(ref, corrupt, "resumed from the previous checkpoint vs uninterrupted")
    # Both unusable: one is truncated, the other corrupted.
    def reopened(name):
        """The finished run's directory as it was before its end, with no checkpoint."""
        d = os.path.join(tmp, name)
        shutil.copytree(corrupt, d)
        os.remove(os.path.join(d, "summary.json"))
        for f in os.listdir(d):
            if f.startswith("checkpoint_"):
                os.remove(os.path.join(d, f))
        return d

    both = reopened("both")
    open(os.path.join(both, os.path.basename(new)), "wb").write(data)
    open(os.path.join(both, os.path.basename(old)), "wb").write(old_bytes[:1000])
    r = run(["run", "--resume", both])
    check(r.returncode == 1 and "no usable checkpoint" in r.stderr and "truncated: 1000 of" in r.stderr
          and "checksum mismatch" in r.stderr
          and len([l for l in r.stderr.splitlines() if l.startswith("rcdem: error: ")]) == 1,
          "no usable checkpoint: one error line naming both files and reasons ("
          + r.stderr.strip().splitlines()[-1] + ")")

    # --- A full disk while resuming: a clear error, the checkpoints intact, then it goes on. --
    full = reopened("full")
    open(os.path.join(full, os.path.basename(old)), "wb").write(old_bytes)  # intact, old_step
    before = old_bytes
    size = len(before)

    def small_disk():
        resource.setrlimit(resource.RLIMIT_FSIZE, (size // 2, size // 2))
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)

    r = run(["run", "--resume", full, "--checkpoint-every", "100"], preexec_fn=small_disk)
    check(r.returncode == 1 and "File too large" in r.stderr and "--resume" in r.stderr
          and len(r.stderr.strip().splitlines()[-1]) > 0,
          f"a full disk is a clear error: {r.stderr.strip().splitlines()[-1] if r.stderr.strip() else ''}")
    check(read_bytes(os.path.join(full, os.path.basename(old))) == before
          and [s for s, _ in checkpoints(full)] == [old_step],
          "the earlier checkpoint is intact and still the only one")
    check(not [f for f in os.listdir(full) if ".tmp." in f], "no temporary file left")
    m = json.load(open(os.path.join(full, "manifest.json")))
    check(m["exit_state"] == "failed" and "File too large" in m.get("error", ""),
          "manifest: failed, with the error")
    r = run(["run", "--resume", full])
    check(r.returncode == 0, "with space again, the run resumes and finishes")
    same_as(ref, full, "after a failed resume, resumed again vs uninterrupted")
    if os.geteuid() != 0:
        ro = os.path.join(tmp, "readonly")
        shutil.copytree(full, ro)
        os.remove(os.path.join(ro, "summary.json"))
        open(os.path.join(ro, os.path.basename(old)), "wb").write(old_bytes)
        os.chmod(ro, 0o555)
        r = run(["run", "--resume", ro])
        os.chmod(ro, 0o755)
        check(r.returncode == 1 and "not writable" in r.stderr, f"an unwritable run directory: {r.stderr.strip()}")

    # --- 1 and 2 threads: the same bits, where the loops really run in parallel. -------------
    cube = os.path.join(tmp, "cube100.toml")
    open(cube, "w").write(
        text.replace("size = [0.05, 0.05, 0.05]", "size = [0.1, 0.1, 0.1]")
        .replace("start = [0.005, 0.025, 0.025]", "start = [0.01, 0.05, 0.05]")
        .replace("end = [0.045, 0.025, 0.025]", "end = [0.09, 0.05, 0.05]")
        .replace("cylinder_length = 0.01", "cylinder_length = 0.02")
        .replace("velocity = -0.5", "velocity = -2.0").replace("ramp_time = 5.0e-5", "ramp_time = 2.0e-5")
        .replace("steps = 3000", "steps = 300").replace("history_rows = 100", "history_rows = 300"))
    one, two = os.path.join(tmp, "t1"), os.path.join(tmp, "t2")
    r1 = run(["run", cube, "-o", one], threads=1)
    r2 = run(["run", cube, "-o", two], threads=2)
    check(r1.returncode == 0 and r2.returncode == 0, "the 100 mm cube runs at 1 and 2 threads")
    s1 = summary(one)
    check(s1["specimen"]["contacts"] > 2048 and s1["damaged_points"] > 0,
          f"{s1['specimen']['contacts']} contacts (> 2048: parallel), {s1['damaged_points']} damaged points")
    check(json.load(open(os.path.join(two, "manifest.json")))["threads"] == 2, "the second ran at 2 threads")
    same_as(one, two, "1 thread vs 2 threads")
    # --threads: auto (the default) follows the free cores up to OMP_NUM_THREADS; N fixes it.
    t2 = json.load(open(os.path.join(two, "summary.json")))["threads"]
    check(t2["tuned"] and t2["max"] == 2 and 1.0 <= t2["mean"] <= 2.0,
          f"by default the count is tuned, up to OMP_NUM_THREADS = 2 ({t2})")
    fixed = os.path.join(tmp, "t1_fixed")
    r = run(["run", cube, "-o", fixed, "--threads", "1"], threads=2)
    t1 = json.load(open(os.path.join(fixed, "summary.json")))["threads"] if r.returncode == 0 else {}
    check(r.returncode == 0 and json.load(open(os.path.join(fixed, "manifest.json")))["threads"] == 1
          and t1 == {"tuned": False, "max": 1, "last": 1, "mean": 1.0, "changes": 0},
          f"--threads 1 runs one thread where OMP_NUM_THREADS is 2 ({t1})")
    same_as(two, fixed, "--threads auto vs --threads 1")
    for bad in ("0", "two", "1.5", "-3"):
        r = run(["run", cube, "-o", os.path.join(tmp, "bad_threads"), "--threads", bad])
        check(r.returncode != 0 and r.stderr.count("\n") == 1 and f"--threads '{bad}'" in r.stderr
              and "expected auto or a whole number" in r.stderr
              and not os.path.exists(os.path.join(tmp, "bad_threads")),
              f"--threads {bad}: one line naming it, nothing written ({r.stderr.strip()})")
finally:
    shutil.rmtree(tmp, ignore_errors=True)

checks.finish()
