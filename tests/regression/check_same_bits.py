#!/usr/bin/python3
"""The same binary gives the same bits on another x86-64 CPU (issue "Trustworthy numbers"): the
quick AN0 beam run twice, once as the machine is and once with glibc told that the CPU lacks AVX2,
FMA and AVX-512 (GLIBC_TUNABLES=glibc.cpu.hwcaps=-AVX2,-FMA,-AVX512F: libm's sin, cos, atan2 and
pow then take their baseline code paths, as on an older x86-64). The portable build (no
-march=native, no contraction) uses no instruction beyond the x86-64 baseline itself, so its
history.csv must be byte-identical. A native build is skipped (77): it is not meant to be
portable.

usage: check_same_bits.py RCDEM_BINARY SOURCE_DIR
"""
import filecmp
import json
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checklist import Checklist  # noqa: E402

rcdem, source = sys.argv[1], sys.argv[2]
version = subprocess.run([rcdem, "--version"], capture_output=True, text=True).stdout
if "portable" not in version:
    print(f"SKIP: '{version.strip()}' is not the portable build")
    sys.exit(77)
checks = Checklist()
check = checks.check
scenario = "examples/three_point_bending/study/quick/AN0.toml"
masked = "glibc.cpu.hwcaps=-AVX2,-FMA,-AVX512F"
with tempfile.TemporaryDirectory() as tmp:
    runs = {}
    for name, tunables in (("as is", None), ("baseline libm", masked)):
        env = dict(os.environ)
        if tunables:
            env["GLIBC_TUNABLES"] = tunables
        out = os.path.join(tmp, name.replace(" ", "_"))
        r = subprocess.run([rcdem, "-q", "run", scenario, "-o", out], cwd=source, env=env,
                           capture_output=True, text=True, timeout=1200)
        check(r.returncode == 0, f"quick AN0 ({name}) exits 0 ({r.stderr.strip()[-300:]})")
        runs[name] = out
    a, b = (os.path.join(runs[n], "history.csv") for n in ("as is", "baseline libm"))
    same = os.path.exists(a) and os.path.exists(b) and filecmp.cmp(a, b, shallow=False)
    peaks = [json.load(open(os.path.join(runs[n], "summary.json")))["peak_load_N"]
             if os.path.exists(os.path.join(runs[n], "summary.json")) else None for n in runs]
    check(same, f"history.csv byte-identical with {masked} (peaks {peaks[0]!r} / {peaks[1]!r} N)")
checks.finish()
