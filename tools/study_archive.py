#!/usr/bin/python3
"""What the study report needs of a study directory's finished runs, in one archive, and back.

usage: study_archive.py pack STUDY_DIR ARCHIVE.tar.xz
       study_archive.py unpack ARCHIVE.tar.xz STUDY_DIR
       study_archive.py pack-runs STUDY_DIR RUNS_DIR
       study_archive.py unpack-runs RUNS_DIR STUDY_DIR

A full-size study takes longer than one working session on a small machine; its runs are
bit-reproducible with the same binary, so a study may be run in parts, and the finished part kept
(docs/case-study.md, "How to run it"). `pack` keeps the study's cases.csv, peak_loads.csv and
study.json, and of each finished run (cases.csv) summary.json, history.csv, broken_points.csv,
manifest.json, scenario.toml and run.log: about a quarter of a megabyte a full-size run, against
hundreds of megabytes with its snapshots (so Figures 8 and 9, drawn from the last snapshot, are
not remade from an archive). The archive's bytes depend only on those files (sorted, no owner or
time stamps). `unpack` writes into a study directory that does not exist or is empty, never over
earlier results; `rcdem study -o STUDY_DIR` then counts those runs as finished and runs the rest.

`pack-runs` writes one archive a finished run, RUNS_DIR/<run>.tar.xz (the same run files, under
cases/<run>/), for each finished run that has none yet, and copies the study's cases.csv,
peak_loads.csv and study.json beside them: a study kept in parts over several sessions adds a
file a run and never rewrites one (tools/regenerate_docs.sh --save). Of a three-point bending
study's first packing's NL-B runs and AN0, whose Figures 8 and 9 a report publishes, it keeps the
two figures drawn from the snapshots (figure8.png, figure9.png in the run's archive), which the
report then uses for a run without snapshots. `unpack-runs` puts each
archived run into STUDY_DIR/cases/<run> where that run is not there yet (never over a run), and
the study's three files where they are missing; `rcdem study -o STUDY_DIR` then counts those runs
as finished, runs the rest and writes its tables again.
"""
import csv
import io
import json
import os
import shutil
import sys
import tarfile

STUDY_FILES = ("cases.csv", "peak_loads.csv", "study.json")
RUN_FILES = ("summary.json", "history.csv", "broken_points.csv", "manifest.json",
             "scenario.toml", "run.log", "figure8.png", "figure9.png")
# The runs of a three-point bending study whose Figures 8 and 9 a report publishes (the first
# packing's NL-B runs and AN0: tools/publish_study.py): pack-runs draws them from the snapshots,
# which it does not keep (tools/study_report.py draw_run_figures).
FIGURE_INTERFACES = ("NL-B", "none")


def finished_runs(study):
    path = os.path.join(study, "cases.csv")
    if not os.path.exists(path):
        sys.exit(f"{study}: no cases.csv (not a study directory, or its study has not run)")
    rows = [r for r in csv.DictReader(open(path)) if r["status"] == "finished"]
    return [r.get("directory") or r["case"] for r in rows]


def add(tar, path, name):
    data = open(path, "rb").read()
    info = tarfile.TarInfo(name)
    info.size, info.mode, info.mtime = len(data), 0o644, 0
    tar.addfile(info, io.BytesIO(data))


def pack(study, archive):
    runs = finished_runs(study)
    if not runs:
        sys.exit(f"{study}: no finished run to pack")
    if os.path.exists(archive):
        sys.exit(f"{archive}: exists (remove it first: an archive is never overwritten)")
    names = [f for f in STUDY_FILES if os.path.exists(os.path.join(study, f))]
    for run in sorted(runs):
        if not os.path.exists(os.path.join(study, "cases", run, "summary.json")):
            sys.exit(f"{study}: cases.csv says {run} finished but it has no summary.json")
        names += [f"cases/{run}/{f}" for f in RUN_FILES
                  if os.path.exists(os.path.join(study, "cases", run, f))]
    with tarfile.open(archive, "w:xz", format=tarfile.PAX_FORMAT) as tar:
        for name in names:
            add(tar, os.path.join(study, name), name)
    print(f"{archive}: {len(runs)} finished runs of {study}, {os.path.getsize(archive):,} bytes")


def safe_members(tar, archive, run=None):
    """The members, each a study file or a run's file (of `run` only, if given), or exit."""
    for m in tar.getmembers():
        parts = m.name.split("/")
        if not m.isfile() or m.name.startswith("/") or ".." in parts or not (
                (run is None and len(parts) == 1 and parts[0] in STUDY_FILES)
                or (len(parts) == 3 and parts[0] == "cases" and parts[2] in RUN_FILES
                    and parts[1] == (run or parts[1]))):
            sys.exit(f"{archive}: {m.name!r} is not a file of "
                     + ("a study archive" if run is None else f"run {run}'s archive"))
        yield m


def unpack(archive, study):
    if os.path.exists(study) and (not os.path.isdir(study) or os.listdir(study)):
        sys.exit(f"{study}: exists and is not an empty directory (an archive is unpacked only "
                 "into a new study directory)")
    try:
        with tarfile.open(archive, "r:xz") as tar:
            members = list(safe_members(tar, archive))
            os.makedirs(study, exist_ok=True)
            for m in members:
                target = os.path.join(study, m.name)
                os.makedirs(os.path.dirname(target), exist_ok=True)
                with open(target, "wb") as f:
                    f.write(tar.extractfile(m).read())
    except (tarfile.TarError, OSError, EOFError) as e:
        sys.exit(f"{archive}: cannot be read as a study archive ({e})")
    print(f"{study}: {len(finished_runs(study))} finished runs from {archive}")


def figure_runs(study):
    """The finished runs of a three-point bending study whose Figures 8 and 9 are published."""
    path = os.path.join(study, "study.json")
    label = json.load(open(path)).get("study", "") if os.path.exists(path) else ""
    if not label.startswith("three_point_bending"):
        return set()
    rows = csv.DictReader(open(os.path.join(study, "cases.csv")))
    return {r.get("directory") or r["case"] for r in rows
            if r["status"] == "finished" and r["interface"] in FIGURE_INTERFACES
            and r.get("seed", "1") in ("", "1")}


def pack_runs(study, runs_dir):
    runs = finished_runs(study)
    os.makedirs(runs_dir, exist_ok=True)
    added = 0
    figures = figure_runs(study)
    for run in sorted(runs):
        archive = os.path.join(runs_dir, run + ".tar.xz")
        if os.path.exists(archive):
            continue
        if not os.path.exists(os.path.join(study, "cases", run, "summary.json")):
            sys.exit(f"{study}: cases.csv says {run} finished but it has no summary.json")
        if run in figures:
            import study_report  # matplotlib and meshio: only where a figure is drawn
            study_report.draw_run_figures(run, os.path.join(study, "cases", run))
        with tarfile.open(archive + ".part", "w:xz", format=tarfile.PAX_FORMAT) as tar:
            for f in RUN_FILES:
                path = os.path.join(study, "cases", run, f)
                if os.path.exists(path):
                    add(tar, path, f"cases/{run}/{f}")
        os.replace(archive + ".part", archive)
        added += 1
    for f in STUDY_FILES:  # the study's own tables, as they are now (small; rewritten each time)
        if os.path.exists(os.path.join(study, f)):
            shutil.copyfile(os.path.join(study, f), os.path.join(runs_dir, f))
    print(f"{runs_dir}: {added} runs of {study} added")


def unpack_runs(runs_dir, study):
    added = 0
    for name in sorted(os.listdir(runs_dir)):
        if not name.endswith(".tar.xz"):
            continue
        run, archive = name[:-len(".tar.xz")], os.path.join(runs_dir, name)
        target = os.path.join(study, "cases", run)
        if os.path.exists(target):
            continue
        try:
            with tarfile.open(archive, "r:xz") as tar:
                members = list(safe_members(tar, archive, run))
                os.makedirs(target + ".part", exist_ok=True)
                for m in members:
                    with open(os.path.join(target + ".part", m.name.split("/")[2]), "wb") as f:
                        f.write(tar.extractfile(m).read())
        except (tarfile.TarError, OSError, EOFError) as e:
            sys.exit(f"{archive}: cannot be read as a run's archive ({e})")
        os.replace(target + ".part", target)
        added += 1
    for f in STUDY_FILES:  # `rcdem study -o` refuses a non-empty directory without study.json
        if os.path.exists(os.path.join(runs_dir, f)) and not os.path.exists(os.path.join(study, f)):
            shutil.copyfile(os.path.join(runs_dir, f), os.path.join(study, f))
    print(f"{study}: {added} runs from {runs_dir}")


COMMANDS = {"pack": pack, "unpack": unpack, "pack-runs": pack_runs, "unpack-runs": unpack_runs}

if __name__ == "__main__":
    if len(sys.argv) != 4 or sys.argv[1] not in COMMANDS:
        sys.exit(__doc__)
    COMMANDS[sys.argv[1]](sys.argv[2], sys.argv[3])
