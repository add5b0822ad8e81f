#!/usr/bin/python3
"""Checkpoints are HDF5 files any reader understands (issue 46; docs/checkpoint.md, "The HDF5
file"), on tests/regression/small_run.toml interrupted by SIGINT after its checkpoints:

  * h5dump reads one; h5py finds the documented attributes, one group per section and in each a
    dataset per column, every one with its unit, shaped by its section's record count;
  * what it holds is the run's: its history rows are history.csv's rows, its broken-point flags
    broken_points.csv's points, its peak at least the history's largest load;
  * it is the binary image, losslessly: rebuilt from h5py alone by the documented layout, the
    image's CRC-32 is the file's 'crc32'; written as a .rcp file (the format before, still read)
    with the .h5 files removed, it resumes, and the run ends with the uninterrupted run's bytes;
  * damaged or foreign HDF5 files named like the newest checkpoint (a value changed, a dataset
    removed, HDF5's own metadata damaged, cut short, another program's file) are rejected with
    the reason before HDF5 reads them (rcdem's header: size and CRC-32), and a dataset removed
    behind a redone header by the layout's checks; the previous checkpoint is taken, and the run
    completes.

usage: check_hdf5_checkpoint.py RCDEM_BINARY SOURCE_DIR
"""
import csv
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import zlib

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checklist import Checklist  # noqa: E402
from checkpoint_image import binary_image, documented_version  # noqa: E402
from interrupted_run import checkpoints, interrupted_run  # noqa: E402

rcdem, source = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
checks = Checklist()
check = checks.check
SCENARIO = open(os.path.join(source, "tests/regression/small_run.toml")).read()


def resume(d):
    return subprocess.run([rcdem, "-q", "run", "--resume", d], capture_output=True, text=True,
                          timeout=120)


def read_csv(path):
    with open(path) as f:
        rows = list(csv.reader(f))
    return rows[0], rows[1:]


with tempfile.TemporaryDirectory() as tmp:
    scenario = os.path.join(tmp, "whole.toml")
    open(scenario, "w").write(SCENARIO)
    whole = os.path.join(tmp, "whole")
    subprocess.run([rcdem, "-q", "run", scenario, "-o", whole], check=True, capture_output=True)

    # Past cracking: points break from step 900 of its 3,000.
    d, _ = interrupted_run(rcdem, SCENARIO, tmp, "stopped", min_step=1200)
    newest = checkpoints(d)[-1]
    step = int(os.path.basename(newest)[11:23])
    h = subprocess.run(["h5dump", "-H", newest], capture_output=True, text=True)
    check(h.returncode == 0 and 'GROUP "bodies"' in h.stdout and 'ATTRIBUTE "unit"' in h.stdout,
          f"h5dump reads {os.path.basename(newest)} (exit {h.returncode})")

    with h5py.File(newest, "r") as f:
        a = f.attrs
        documented = documented_version(source)
        check(a["format"] == "rcdem checkpoint" and int(a["version"]) == documented and
              int(a["step"]) == step and a["writer"].startswith("rcdem "),
              f"h5py: the root's attributes (format, version {int(a['version'])}: "
              f"docs/checkpoint.md's {documented}, step {step}, writer)")
        bad = []
        for name, g in f.items():
            count = int(g.attrs["count"])
            for col, ds in g.items():
                if "unit" not in ds.attrs and g.attrs["kind"] == "words":
                    bad.append(f"{name}/{col}: no unit")
                if ds.shape and ds.shape[0] != count:
                    bad.append(f"{name}/{col}: {ds.shape[0]} records, section {count}")
        check(not bad and len(f) >= 10, f"{len(f)} sections, every column with its unit and "
              f"its section's record count ({bad[:3]})")
        units = {k: f["bodies"][k].attrs["unit"] for k in ("position", "velocity", "orientation")}
        check(units == {"position": "m", "velocity": "m/s", "orientation": "1"} and
              f["bodies/position"].shape[1] == 3 and f["bodies/orientation"].shape[1] == 4,
              f"bodies: position (n, 3) in m, velocity in m/s, orientation (n, 4) ({units})")
        cols, rows = read_csv(os.path.join(d, "history.csv"))
        held = f["history/row"][()]
        check(f["history.columns/text"][()].decode() == ",".join(cols) and
              held.shape == (len(rows), len(cols)) and
              np.allclose(held, np.array(rows, dtype=float), rtol=1e-9, atol=0.0),
              f"its {held.shape[0]} history rows are history.csv's (to its 10 digits)")
        broken = int(np.count_nonzero(f["cracks.broken/bytes"][()]))
        _, points = read_csv(os.path.join(d, "broken_points.csv"))
        check(broken == len(points) and broken > 0,
              f"its broken-point flags ({broken}) are broken_points.csv's points ({len(points)})")
        load = np.array(rows, dtype=float)[:, cols.index("load_N")]
        check(float(f["run/peak"][0]) >= load.max() > 0.0,
              f"its peak {float(f['run/peak'][0]):.1f} N is at least the history's largest load "
              f"{load.max():.1f} N")

    image = binary_image(newest)
    crc = struct.unpack("<I", image[-4:])[0]
    check(zlib.crc32(image[:-4]) == crc,
          f"rebuilt from h5py by the documented layout, the binary image's CRC-32 is the file's "
          f"({crc:08x})")
    # The binary format (.rcp), still read: the run resumed from it alone ends as the whole run.
    old = os.path.join(tmp, "old_format")
    shutil.copytree(d, old)
    for c in checkpoints(old):
        os.remove(c)
    open(os.path.join(old, f"checkpoint_{step:012d}.rcp"), "wb").write(image)
    r = resume(old)
    same = all(open(os.path.join(old, n), "rb").read() == open(os.path.join(whole, n), "rb").read()
               for n in ("history.csv", "broken_points.csv"))
    check(r.returncode == 0 and os.path.exists(os.path.join(old, "summary.json")),
          f"resumed from the .rcp file alone (exit {r.returncode}: {r.stderr.strip()[-200:]})")
    check(same, "... history.csv and broken_points.csv equal the uninterrupted run's")

    def damaged(label, damage, reason):
        case = os.path.join(tmp, "damaged_" + label)
        shutil.copytree(d, case)
        bad_file = os.path.join(case, "checkpoint_999999999999.h5")
        damage(bad_file)
        r = resume(case)
        check(r.returncode == 0 and "999999999999" in r.stderr and "rejected" in r.stderr and
              reason in r.stderr and os.path.exists(os.path.join(case, "summary.json")),
              f"{label}: rejected ('{reason}'), the previous checkpoint taken, the run completes "
              f"(exit {r.returncode}: {r.stderr.strip()[-200:]})")

    def changed_value(p):
        shutil.copy(newest, p)
        with h5py.File(p, "r+") as f:
            f["bodies/position"][0, 0] += 1e-9
    damaged("a value changed", changed_value, "checksum mismatch")

    def removed_dataset(p):
        shutil.copy(newest, p)
        with h5py.File(p, "r+") as f:
            del f["bodies/velocity"]
    damaged("a dataset removed", removed_dataset, "checksum mismatch")

    def resealed(p):
        """... and rcdem's header made to match again: HDF5 reads it, rcdem's layout checks
        reject it."""
        removed_dataset(p)
        data = bytearray(open(p, "rb").read())
        data[16:24] = struct.pack("<Q", len(data))
        data[12:16] = struct.pack("<I", zlib.crc32(data[24:]))
        open(p, "wb").write(data)
    damaged("a dataset removed, the header's checksum redone", resealed,
            "malformed: group 'bodies''s datasets hold 19 words a record, its width is 22")

    def flipped(p):
        data = bytearray(open(newest, "rb").read())
        for at in (600, 700, 2000):  # HDF5's superblock and root group
            data[at] ^= 0x20
        open(p, "wb").write(data)
    damaged("HDF5's metadata damaged", flipped, "checksum mismatch")

    def cut_short(p):
        data = open(newest, "rb").read()
        open(p, "wb").write(data[:len(data) * 3 // 4])
    damaged("cut short", cut_short, "truncated: ")

    def foreign(p):
        with h5py.File(p, "w") as f:
            f["x"] = np.arange(3.0)
    damaged("another program's HDF5 file", foreign, "not an rcdem checkpoint")

checks.finish()
