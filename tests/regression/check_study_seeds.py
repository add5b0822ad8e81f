#!/usr/bin/python3
"""A study over several packings (issue 27): `rcdem study three_point_bending --quick --cases AN0
--seeds 1,2` runs the quick AN0 beam on two packings, each in its own directory with the seed in
its scenario.toml; peak_loads.csv and cases.csv carry the seed; report.json and table3.md give
the mean, standard deviation and range, consistent with the runs; Figure 10 draws the band. The
seed-1 run is the scenario file's own run to the byte, seed 2 another packing; calling again with
--seeds 1,2,3 runs only seed 3; a report over two study directories (tools/study_report.py -o)
equals the one directory's, and so does the report of the runs packed and unpacked
(tools/study_archive.py), where the study then runs only what is missing; `rcdem run --seed`
refuses what it must.

usage: check_study_seeds.py RCDEM_BINARY SOURCE_DIR
"""
import csv
import filecmp
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checklist import Checklist  # noqa: E402



def without_wall_times(obj):
    """report.json less its wall times: two runs of one packing differ in nothing else."""
    if isinstance(obj, dict):
        return {k: without_wall_times(v) for k, v in obj.items() if k != "wall_time_s"}
    return [without_wall_times(v) for v in obj] if isinstance(obj, list) else obj


def table_without_wall_times(path):
    """table3.md with the cells of every column headed "wall" blanked."""
    lines, blank = [], set()
    for line in open(path).read().splitlines():
        cells = line.split("|")
        if not line.startswith("|"):
            blank = set()
        elif any("wall" in c for c in cells):
            blank = {i for i, c in enumerate(cells) if "wall" in c}
        else:
            cells = ["" if i in blank else c for i, c in enumerate(cells)]
        lines.append("|".join(cells))
    return lines


rcdem, source = sys.argv[1], sys.argv[2]
checks = Checklist()
check = checks.check
scenario = os.path.join(source, "examples", "three_point_bending", "study", "quick", "AN0.toml")
# Loaded 4x faster than the study's quasi-static rate, in every run below: what is checked is the
# study's bookkeeping over packings, and the beam is run six times.
FAST = ["--set", "plates.load.velocity=-0.05"]

with tempfile.TemporaryDirectory() as tmp:
    out = os.path.join(tmp, "study")
    cmd = [rcdem, "study", "three_point_bending", "--quick", "--cases", "AN0", "-o", out, *FAST]
    r = subprocess.run(cmd + ["--seeds", "1,2"], capture_output=True, text=True, timeout=900,
                       cwd=source)
    check(r.returncode == 0, f"the two-seed quick AN0 study exits 0 ({r.stderr.strip()[-300:]})")
    runs = {s: os.path.join(out, "cases", f"AN0_seed{s}") for s in (1, 2)}
    peaks = list(csv.DictReader(open(os.path.join(out, "peak_loads.csv"))))
    check(peaks and list(peaks[0]) == ["case", "directory", "variant", "model", "interface", "seed",
                                       "peak_load_N", "deflection_at_peak_m"]
          and sorted(p["seed"] for p in peaks) == ["1", "2"]
          and sorted(p["directory"] for p in peaks) == ["AN0_seed1", "AN0_seed2"],
          "peak_loads.csv has a seed column and one row per packing, each naming its run")
    cases = list(csv.DictReader(open(os.path.join(out, "cases.csv"))))
    check([(c["case"], c["seed"], c["directory"]) for c in cases]
          == [("AN0", "1", "AN0_seed1"), ("AN0", "2", "AN0_seed2")],
          "cases.csv names each run's case, seed and directory")
    for s, d in runs.items():
        text = open(os.path.join(d, "scenario.toml")).read()
        check(f"\nseed = {s}\n" in text, f"seed {s}: its scenario.toml holds seed = {s}")
    # Seed 1 is the file's own seed: the same run as `rcdem run` of the file, to the byte.
    plain = os.path.join(tmp, "plain")
    r = subprocess.run([rcdem, "-q", "run", scenario, "-o", plain, *FAST], capture_output=True, text=True,
                       timeout=600, cwd=source)
    same = r.returncode == 0 and filecmp.cmp(os.path.join(plain, "history.csv"),
                                             os.path.join(runs[1], "history.csv"), shallow=False)
    check(same, "seed 1's history.csv equals a plain run of the scenario byte for byte")
    check(not filecmp.cmp(os.path.join(runs[1], "history.csv"),
                          os.path.join(runs[2], "history.csv"), shallow=False),
          "seed 2 is another packing (its history differs)")
    values = [float(p["peak_load_N"]) for p in sorted(peaks, key=lambda p: p["seed"])]
    rep = json.load(open(os.path.join(out, "report.json")))
    e = rep["ensembles"]["AN0"]["peak_load_N"]
    # peak_loads.csv keeps 9 digits, the report reads the runs' summaries.
    near = (lambda a, b: abs(a - b) < 1e-7 * abs(b))
    check(e["n"] == 2 and near(e["mean"], statistics.mean(values))
          and abs(e["sd"] - statistics.stdev(values)) < 1e-7 * e["mean"]
          and near(e["min"], min(values)) and near(e["max"], max(values)),
          f"report.json: the peak's mean {e['mean']:.1f} N, sd {e['sd']:.1f} N, range of the two runs")
    check(e["min"] <= e["mean"] <= e["max"], "the mean lies within [min, max]")
    d = rep["ensembles"]["AN0"]["deflection_at_peak_m"]
    check(d["n"] == 2 and d["min"] <= d["mean"] <= d["max"], "the deflection at peak likewise")
    table = open(os.path.join(out, "table3.md")).read()
    check(f"{e['mean'] / 1e3:.1f} ± {e['sd'] / 1e3:.1f}" in table
          and "## Each case over its packings" in table,
          "table3.md gives mean ± sd and the per-case ensemble table")
    for f in ("figure10_AN0.png", "figure10f_NL-B.png", "figure9_AN0_seed1.png",
              "figure9_AN0_seed2.png", "curves/AN0_seed1.csv", "curves/AN0_seed2.csv"):
        path = os.path.join(out, f)
        check(os.path.exists(path) and os.path.getsize(path) > 0, f"{f} written")
    # Another study directory with seed 3 alone, and one report over both (-o): the same report,
    # to the byte, as the one directory that the resume below fills with seeds 1, 2 and 3.
    out3 = os.path.join(tmp, "study3")
    r = subprocess.run([rcdem, "study", "three_point_bending", "--quick", "--cases", "AN0", "-o",
                        out3, "--seeds", "3", *FAST], capture_output=True, text=True, timeout=900,
                       cwd=source)
    check(r.returncode == 0, "a second study directory with seed 3 alone")
    merged = os.path.join(tmp, "merged")
    report = [sys.executable, os.path.join(source, "tools", "study_report.py")]
    r = subprocess.run(report + ["-o", merged, out, out3], capture_output=True, text=True,
                       timeout=600)
    merged_cases = list(csv.DictReader(open(os.path.join(merged, "cases.csv"))))
    check(r.returncode == 0 and [(c["study"], c["seed"]) for c in merged_cases]
          == [(os.path.abspath(out), "1"), (os.path.abspath(out), "2"), (os.path.abspath(out3), "3")],
          "a report over two study directories: cases.csv holds both, each row naming its study")
    # Resumable per (case, seed): the finished packings are kept, only the new one runs.
    before = os.path.getmtime(os.path.join(runs[1], "summary.json"))
    r = subprocess.run(cmd + ["--seeds", "1,2,3"], capture_output=True, text=True, timeout=900,
                       cwd=source)
    check(r.returncode == 0 and r.stderr.count("finished earlier") == 2
          and "AN0 (seed 3): started" in r.stderr
          and os.path.getmtime(os.path.join(runs[1], "summary.json")) == before,
          "--seeds 1,2,3 keeps seeds 1 and 2 and runs seed 3")
    rep = json.load(open(os.path.join(out, "report.json")))
    check(rep["ensembles"]["AN0"]["peak_load_N"]["n"] == 3, "the report then covers 3 packings")
    check(filecmp.cmp(os.path.join(out3, "cases", "AN0_seed3", "history.csv"),
                      os.path.join(out, "cases", "AN0_seed3", "history.csv"), shallow=False),
          "seed 3 runs to the same bits in either directory")
    check(without_wall_times(json.load(open(os.path.join(merged, "report.json"))))
          == without_wall_times(rep)
          and table_without_wall_times(os.path.join(merged, "table3.md"))
          == table_without_wall_times(os.path.join(out, "table3.md")),
          "the report over both directories equals the report of the one holding seeds 1, 2 and 3 "
          "(but for the wall times of the two runs of seed 3)")
    docs = os.path.join(tmp, "docs")
    r = subprocess.run([sys.executable, os.path.join(source, "tools", "publish_study.py"), merged,
                        docs], capture_output=True, text=True, timeout=60)
    table = open(os.path.join(docs, "cases.md")).read() if r.returncode == 0 else ""
    steps = sum(int(c["steps"]) for c in merged_cases)
    check(all(os.path.exists(os.path.join(docs, f)) for f in
              ("table3.md", "report.json", "cases.csv", "figure10_AN0.png", "figure9_AN0_seed1.png"))
          and rep["commit"] in table and table.count("\n| AN0 |") == 3
          and f"| all 3 runs (sums) | | {steps:,} |" in table,
          "publish_study.py copies the tables and figures and writes cases.md: one row a run, "
          "the sum of their steps, the commit")
    r = subprocess.run(report + ["-o", merged, out, out3], capture_output=True, text=True,
                       timeout=600)
    check(r.returncode != 0 and "AN0 on seed 3 is in both" in r.stderr,
          "a packing in two of the studies is refused, naming it")
    # The finished runs in an archive (tools/study_archive.py): the same report from it, and a
    # study continued from it runs only what is missing.
    tool = [sys.executable, os.path.join(source, "tools", "study_archive.py")]
    archive, unpacked = os.path.join(tmp, "study.tar.xz"), os.path.join(tmp, "unpacked")
    rc = [subprocess.run(c, capture_output=True, text=True, timeout=600).returncode for c in
          (tool + ["pack", out, archive], tool + ["unpack", archive, unpacked], report + [unpacked])]
    check(rc == [0, 0, 0] and json.load(open(os.path.join(unpacked, "report.json"))) == rep
          and filecmp.cmp(os.path.join(unpacked, "table3.md"), os.path.join(out, "table3.md"),
                          shallow=False),
          f"packed and unpacked, the three runs give the same report.json and table3.md ({rc})")
    r = subprocess.run([rcdem, "study", "three_point_bending", "--quick", "--cases", "AN0", "-o",
                        unpacked, "--seeds", "1,2,3,4", *FAST], capture_output=True, text=True,
                       timeout=900, cwd=source)
    check(r.returncode == 0 and r.stderr.count("finished earlier") == 3
          and os.path.exists(os.path.join(unpacked, "cases", "AN0_seed4", "summary.json")),
          "the study continued in the unpacked directory keeps its 3 runs and runs seed 4 only")
    again = [subprocess.run(tool + args, capture_output=True, text=True, timeout=60) for args in
             (["unpack", archive, unpacked], ["pack", out, archive])]
    check(again[0].returncode != 0 and "not an empty directory" in again[0].stderr
          and again[1].returncode != 0 and "never overwritten" in again[1].stderr,
          "an archive is not unpacked over a study, nor packed over an archive")
    # One archive a run (pack-runs, unpack-runs: a study kept in parts over fresh machines).
    runs_dir, parts = os.path.join(tmp, "runs"), os.path.join(tmp, "parts")
    packed = [subprocess.run(tool + ["pack-runs", out, runs_dir], capture_output=True, text=True,
                             timeout=600) for _ in range(2)]
    kept = sorted(os.listdir(runs_dir)) if os.path.isdir(runs_dir) else []
    check([p.returncode for p in packed] == [0, 0] and "3 runs" in packed[0].stdout
          and "0 runs" in packed[1].stdout
          and kept == [f"AN0_seed{s}.tar.xz" for s in (1, 2, 3)]
          + ["cases.csv", "peak_loads.csv", "study.json"],
          f"pack-runs writes one archive a finished run, and none again, and the study's own "
          f"tables ({kept})")
    r = subprocess.run(tool + ["unpack-runs", runs_dir, parts], capture_output=True, text=True,
                       timeout=600)
    cont = subprocess.run(cmd[:-3] + [parts, "--seeds", "1,2,3", *FAST], capture_output=True,
                          text=True, timeout=600, cwd=source)
    same = cont.returncode == 0 and filecmp.cmp(
        os.path.join(parts, "peak_loads.csv"), os.path.join(out, "peak_loads.csv"), shallow=False)
    check(r.returncode == 0 and cont.stderr.count("finished earlier") == 3 and same,
          "unpack-runs gives a study its 3 runs: it runs none and writes the same peak_loads.csv "
          f"({r.returncode}, {cont.returncode}: {cont.stderr.strip()[-300:]})")
    kept = [os.path.exists(os.path.join(parts, f"figure{n}_AN0_seed{s}.png"))
            for s in (1, 2) for n in (8, 9)]
    check(kept == [True, True, False, False],
          f"the runs kept without snapshots: packing 1's Figures 8 and 9 kept, drawn at pack-runs, "
          f"and the report over them uses them; none for packing 2 ({kept})")
    again = subprocess.run(tool + ["unpack-runs", runs_dir, parts], capture_output=True,
                           text=True, timeout=60)
    check(again.returncode == 0 and "0 runs" in again.stdout, "unpack-runs never writes over a run")
    bad_runs = os.path.join(tmp, "bad_runs")
    os.makedirs(bad_runs)
    shutil.copy(archive, os.path.join(bad_runs, "AN0_seed1.tar.xz"))  # a whole study's archive
    bad = subprocess.run(tool + ["unpack-runs", bad_runs, os.path.join(tmp, "bad_parts")],
                         capture_output=True, text=True, timeout=60)
    check(bad.returncode != 0 and "is not a file of run AN0_seed1's archive" in bad.stderr,
          "a run's archive holding other files is refused, naming the file")
    # Refusals.
    bad = subprocess.run(cmd + ["--seeds", "2,2"], capture_output=True, text=True, timeout=60,
                         cwd=source)
    check(bad.returncode == 1 and "seed 2 is given twice" in bad.stderr, "a repeated seed is refused")
    bad = subprocess.run([rcdem, "run", "--resume", runs[1], "--seed", "3"], capture_output=True,
                         text=True, timeout=60, cwd=source)
    check(bad.returncode == 1 and "--seed" in bad.stderr, "--resume with --seed is refused")
checks.finish()
