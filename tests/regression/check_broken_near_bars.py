#!/usr/bin/python3
"""tools/broken_near_bars.py on a hand-made run directory whose answer is known: one bar along x at
y = 0.0375, z = 0.01 (D = 10 mm, so "near" is within 19 mm of its axis), four broken points (two
near it, one far, one near but broken after the deflection asked for), and a bad input.

usage: check_broken_near_bars.py SOURCE_DIR
"""
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checklist import Checklist  # noqa: E402

source = sys.argv[1]
tool = os.path.join(source, "tools", "broken_near_bars.py")
checks = Checklist()
check = checks.check

with tempfile.TemporaryDirectory() as run:
    with open(os.path.join(run, "scenario.toml"), "w") as f:
        f.write('[bars.bar1]\nstart = [0.01, 0.0375, 0.01]\nend = [0.69, 0.0375, 0.01]\n'
                'diameter = 0.01\n')
    with open(os.path.join(run, "broken_points.csv"), "w") as f:
        f.write("x_m,y_m,z_m,area_m2,step,deflection_m,load_N\n"
                "0.35,0.0375,0.0,1e-6,10,-0.0002,1000\n"      # 10 mm below the axis: near
                "0.30,0.050,0.02,2e-6,20,-0.0003,1200\n"      # 16 mm away: near
                "0.35,0.0375,0.09,4e-6,30,-0.0004,1300\n"     # 80 mm above: elsewhere
                "0.36,0.0375,0.005,8e-6,40,-0.0012,1400\n")   # near, but broken at 1.2 mm
    with open(os.path.join(run, "history.csv"), "w") as f:
        f.write("step,load_displacement_m,broken_interface_points\n0,0,0\n10,-0.0005,3\n"
                "20,-0.0011,7\n")
    r = subprocess.run(["/usr/bin/python3", tool, run, "--at", "1.0", "2.0"],
                       capture_output=True, text=True)
    lines = r.stdout.splitlines()
    check(r.returncode == 0 and len(lines) == 2, f"two lines, exit 0 ({r.stderr.strip()})")
    kv = [dict(p.split("=", 1) for p in line.split()) for line in lines]
    if len(kv) == 2:
        a, b = kv
        check(a["near_bars"] == "2" and a["elsewhere"] == "1",
              f"by 1.0 mm: 2 near the bar, 1 elsewhere ({a['near_bars']}, {a['elsewhere']})")
        check(abs(float(a["near_area_m2"]) - 3e-6) < 1e-12, "their areas summed (3e-6 m2)")
        check(a["broken_interface_points"] == "3", "interface points broken by 1.0 mm: 3")
        check(b["near_bars"] == "3" and b["broken_interface_points"] == "7",
              "by 2.0 mm: the late point counted too, and 7 interface points")
    os.remove(os.path.join(run, "scenario.toml"))
    r = subprocess.run(["/usr/bin/python3", tool, run], capture_output=True, text=True)
    check(r.returncode == 1 and "scenario.toml" in r.stderr and "Traceback" not in r.stderr,
          f"a missing scenario.toml: one message naming it, exit 1 ({r.stderr.strip()})")
checks.finish()
