#!/usr/bin/python3
"""End-to-end check of `rcdem calibrate` on a 50 mm cube (fast, not quasi-static: --rate-factor 4;
the real figures are in docs/calibration.md): calibration.json holds E, nu, sigma_c, sigma_t in SI
within broad bounds, the curves are written, and the contact fragment works through `include`.

usage: check_calibrate.py RCDEM_BINARY SOURCE_DIR
"""
import json
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checklist import Checklist  # noqa: E402

rcdem, source = sys.argv[1], sys.argv[2]
checks = Checklist()
check = checks.check



with tempfile.TemporaryDirectory() as tmp:
    out = os.path.join(tmp, "cal")
    r = subprocess.run([rcdem, "-q", "calibrate", os.path.join(source, "examples/uniaxial/cube160.toml"),
                        "--size", "0.05", "--peak-only", "--rate-factor", "4", "-o", out],
                       capture_output=True, text=True, timeout=900)
    check(r.returncode == 0, f"calibrate exits 0 ({r.stderr.strip()[-300:]})")
    j = json.load(open(os.path.join(out, "calibration.json")))
    for key, lo, hi in (("E", 20e9, 60e9), ("nu", 0.05, 0.3), ("sigma_c", 40e6, 200e6),
                        ("sigma_t", 1.5e6, 10e6)):
        check(lo < j[key] < hi, f"{key} = {j[key]:.4g} (SI) in ({lo:.3g}, {hi:.3g})")
    for f in ("curve_compression.csv", "curve_tension.csv", "calibrated_contact.toml"):
        check(os.path.exists(os.path.join(out, f)), f"{f} written")
    scen = os.path.join(tmp, "uses_fragment.toml")
    with open(scen, "w") as f:
        f.write('include = ["cal/calibrated_contact.toml"]\n[specimen]\nshape = "box"\n'
                'size = [0.03, 0.03, 0.03]\n[generation]\nrelaxation_iterations = 10\n')
    r = subprocess.run([rcdem, "-q", "generate", scen, "-o", os.path.join(tmp, "gen")],
                       capture_output=True, text=True, timeout=120)
    check(r.returncode == 0, f"a scenario including the fragment is accepted ({r.stderr.strip()})")

    # Without --size the cube is the scenario's own when its specimen is a cube.
    cube50 = os.path.join(tmp, "cube50.toml")
    text = open(os.path.join(source, "examples/uniaxial/cube160.toml")).read()
    with open(cube50, "w") as f:
        f.write(text.replace("size = [0.160, 0.160, 0.160]", "size = [0.05, 0.05, 0.05]"))
    out50 = os.path.join(tmp, "cal50")
    r = subprocess.run([rcdem, "-q", "calibrate", cube50, "--peak-only", "--rate-factor", "4",
                        "-o", out50], capture_output=True, text=True, timeout=900)
    j50 = json.load(open(os.path.join(out50, "calibration.json"))) if r.returncode == 0 else {}
    check(all(j50.get(k) == j[k] for k in ("E", "nu", "sigma_c", "sigma_t")),
          "calibrate without --size on a 50 mm cube's scenario tests that cube (the same bits as "
          f"--size 0.05: {j50.get('sigma_t')} against {j['sigma_t']})")

checks.finish()
