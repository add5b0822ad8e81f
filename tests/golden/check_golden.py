#!/usr/bin/python3
"""Golden regression curves (issue "Trustworthy numbers"): small reference cases stored with their
expected results (tests/golden/cases/*.toml, the model is LAMMPS's force-style YAML files). Each
case runs one scenario with `rcdem run` and compares what it measures (peak load, displacement at
peak, E and nu, the load sampled at fixed displacements, ...) with the stored values.

Tolerance: bitwise. A reference holds the build that wrote it (`rcdem --version`); the default
build is portable with no floating-point contraction (CMakePresets.json "release"), so the same
source gives the same bits on any x86-64 machine with the same compiler. A run by another build
(native, another compiler) is reported as skipped (exit 77), never compared loosely.

usage:
  check_golden.py RCDEM SOURCE_DIR [--case NAME ...]             compare (exit 1 on a mismatch)
  check_golden.py RCDEM SOURCE_DIR --update [--case NAME ...]    rewrite the references on purpose
  check_golden.py RCDEM SOURCE_DIR --case NAME --set KEY=FACTOR  scale scenario numbers (a
                                                                 sensitivity check: must fail)
"""
import argparse
import datetime
import glob
import json
import math
import os
import subprocess
import sys
import tempfile
import tomllib

SKIP = 77


def toml_value(v):
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, float):
        return repr(v) if math.isfinite(v) else ("nan" if v != v else ("inf" if v > 0 else "-inf"))
    if isinstance(v, int):
        return str(v)
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, list):
        return "[" + ", ".join(toml_value(x) for x in v) + "]"
    raise TypeError(f"cannot write {type(v)} to TOML")


def toml_dump(d, prefix=""):
    """A small TOML writer: scalars and arrays first, then sub-tables (enough for scenarios and
    references)."""
    out = []
    for k, v in d.items():
        if not isinstance(v, dict):
            out.append(f"{k} = {toml_value(v)}")
    for k, v in d.items():
        if isinstance(v, dict):
            name = f"{prefix}{k}"
            out.append(f"\n[{name}]")
            out.append(toml_dump(v, name + "."))
    return "\n".join(x for x in out if x != "")


def perturbed_scenario(source, scenario, scalings, tmp):
    """The scenario with its includes merged in and numbers scaled ([(key, factor)]), written to
    tmp."""
    def load(path):
        with open(path, "rb") as f:
            d = tomllib.load(f)
        merged = {}
        for inc in d.pop("include", []):
            deep_merge(merged, load(os.path.join(os.path.dirname(path), inc)))
        deep_merge(merged, d)
        return merged

    d = load(os.path.join(source, scenario))
    for key, factor in scalings:
        node = d
        parts = key.split(".")
        for p in parts[:-1]:
            node = node[p]
        node[parts[-1]] = node[parts[-1]] * factor
    path = os.path.join(tmp, "perturbed.toml")
    with open(path, "w") as f:
        f.write(toml_dump(d) + "\n")
    return path


def deep_merge(a, b):
    for k, v in b.items():
        if isinstance(v, dict) and isinstance(a.get(k), dict):
            deep_merge(a[k], v)
        else:
            a[k] = v


def read_history(path):
    with open(path) as f:
        cols = f.readline().strip().split(",")
        rows = [[float(x) for x in line.split(",")] for line in f if line.strip()]
    return {c: [r[i] for r in rows] for i, c in enumerate(cols)}


def interpolate(xs, ys, x):
    """y at x on the first segment of the (monotone in its rising part) curve that reaches x."""
    for i in range(1, len(xs)):
        if xs[i] >= x:
            if xs[i] == xs[i - 1]:
                return ys[i]
            t = (x - xs[i - 1]) / (xs[i] - xs[i - 1])
            return ys[i - 1] + t * (ys[i] - ys[i - 1])
    return None  # the run ended before x


def measure(case, out):
    """What the case compares: scalars from summary.json and the history, and the load sampled at
    the case's fixed displacements."""
    s = json.load(open(os.path.join(out, "summary.json")))
    h = read_history(os.path.join(out, "history.csv"))
    control = s["control"]
    col = next(c for c in (f"{control}_displacement_m", f"{control}_pull_displacement_m") if c in h)
    disp = [abs(x) for x in h[col]]
    load = h["load_N"]
    v = {}
    for name in case["measure"]["values"]:
        if name == "peak_load_N":
            v[name] = s["peak_load_N"]
        elif name == "displacement_at_peak_m":
            v[name] = abs(s["displacement_at_peak_m"])
        elif name == "energy_balance_error":
            v[name] = s["energy"]["balance_error"]
        elif name in ("broken_points", "damaged_points", "steps"):
            v[name] = s[name]
        elif name == "final_load_N":
            v[name] = load[-1]
        elif name in ("E_interior_Pa", "nu_interior", "E_face_Pa", "nu_face"):
            # A uniaxial test along z: the last row's stress over the loaded face, and the gauges.
            area = s["gauges"]["face_area_m2"][5]
            gauge = "interior_strain_" if "interior" in name else "strain_"
            ex, ey, ez = (h[gauge + a][-1] for a in "xyz")
            v[name] = (load[-1] / area) / abs(ez) if name.startswith("E") else -0.5 * (ex + ey) / ez
        else:
            raise SystemExit(f"{case['name']}: unknown measure '{name}'")
    xs = case["measure"].get("displacements_m", [])
    curve = [interpolate(disp, load, x) for x in xs]
    return v, xs, curve


def run_case(rcdem, source, case, tmp, scenario=None):
    out = os.path.join(tmp, case["name"])
    cmd = [rcdem, "-q", "run", scenario or case["scenario"], "-o", out]
    r = subprocess.run(cmd, cwd=source, capture_output=True, text=True, timeout=1800)
    if r.returncode != 0:
        raise SystemExit(f"{case['name']}: rcdem exited {r.returncode}: {r.stderr.strip()[-600:]}")
    return out


def compare(case, ref, v, curve):
    """Lines of differences (empty when bitwise equal)."""
    bad = []
    for k, want in ref["values"].items():
        got = v.get(k)
        if got != want:
            rel = abs(got - want) / abs(want) if want else float("inf")
            bad.append(f"{k}: {got!r} against {want!r} (relative {rel:.3g})")
    for x, want, got in zip(case["measure"].get("displacements_m", []), ref.get("load_N", []),
                            curve):
        if got is None:
            bad.append(f"load at {x * 1e3:.4g} mm: the run ended before it (reference {want!r})")
        elif got != want:
            rel = abs(got - want) / abs(want) if want else float("inf")
            bad.append(f"load at {x * 1e3:.4g} mm: {got!r} N against {want!r} (relative {rel:.3g})")
    return bad


def version(rcdem):
    r = subprocess.run([rcdem, "--version"], capture_output=True, text=True)
    text = r.stdout.strip()  # "rcdem 0.1.0 (HASH, BUILD)"
    inner = text[text.index("(") + 1:text.rindex(")")]
    git, build = inner.split(", ", 1)
    return git, build


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("rcdem")
    ap.add_argument("source")
    ap.add_argument("--case", action="append", help="only these cases (default: all)")
    ap.add_argument("--update", action="store_true", help="rewrite the references")
    ap.add_argument("--set", action="append",
                    help="KEY=FACTOR: scale one number of the scenario (sensitivity; repeatable)")
    ap.add_argument("--keep", help="run in this directory instead of a temporary one")
    a = ap.parse_args()
    rcdem, source = os.path.abspath(a.rcdem), os.path.abspath(a.source)
    git, build = version(rcdem)
    files = sorted(glob.glob(os.path.join(source, "tests", "golden", "cases", "*.toml")))
    cases = []
    for path in files:
        with open(path, "rb") as f:
            c = tomllib.load(f)
        c["name"], c["path"] = os.path.splitext(os.path.basename(path))[0], path
        if not a.case or c["name"] in a.case:
            cases.append(c)
    if a.case and len(cases) != len(a.case):
        raise SystemExit(f"unknown case among {a.case}; cases: "
                         + ", ".join(os.path.splitext(os.path.basename(p))[0] for p in files))
    failed = skipped = 0
    tmp_ctx = tempfile.TemporaryDirectory() if not a.keep else None
    tmp = a.keep or tmp_ctx.name
    os.makedirs(tmp, exist_ok=True)
    for case in cases:
        ref = case.get("reference", {})
        if not a.update and ref.get("build") != build:
            print(f"SKIP {case['name']}: this rcdem is '{build}', the reference was written by "
                  f"'{ref.get('build')}' (build with `cmake --preset release`)")
            skipped += 1
            continue
        scenario = None
        if a.set:
            scalings = [(k, float(f)) for k, f in (item.split("=") for item in a.set)]
            scenario = perturbed_scenario(source, case["scenario"], scalings, tmp)
        out = run_case(rcdem, source, case, tmp, scenario)
        v, xs, curve = measure(case, out)
        if a.update:
            if None in curve:
                raise SystemExit(f"{case['name']}: the run ends before the last sampled "
                                 "displacement; shorten measure.displacements_m")
            write_reference(case, git, build, v, curve)
            print(f"updated {case['name']}: " + ", ".join(f"{k} = {x:.6g}" for k, x in v.items()))
            continue
        bad = compare(case, ref, v, curve)
        if bad:
            failed += 1
            print(f"FAIL {case['name']} (reference {ref.get('git_hash')}, {ref.get('date')}):")
            for line in bad:
                print(f"     {line}")
        else:
            print(f"ok   {case['name']}: {len(ref['values'])} values and {len(curve)} curve points "
                  "bitwise equal to the reference")
    if tmp_ctx:
        tmp_ctx.cleanup()
    if failed:
        sys.exit(1)
    if skipped and skipped == len(cases):
        sys.exit(SKIP)


def write_reference(case, git, build, v, curve):
    """Rewrites the case file's [reference] table, keeping its [case]-level keys and comments
    above the first table header that belongs to the reference."""
    with open(case["path"]) as f:
        text = f.read()
    head = text.split("\n[reference]")[0].rstrip()
    marker = "# Written by tests/golden/check_golden.py --update; compared bitwise."
    while head.endswith(marker):  # this function's own line from the last update
        head = head[: -len(marker)].rstrip()
    head += "\n"
    ref = {"git_hash": git, "build": build, "date": datetime.date.today().isoformat(),
           "load_N": curve, "values": v}
    body = "\n# Written by tests/golden/check_golden.py --update; compared bitwise.\n[reference]\n"
    body += toml_dump(ref, "reference.") + "\n"
    with open(case["path"], "w") as f:
        f.write(head + body)


if __name__ == "__main__":
    main()
