#!/usr/bin/python3
"""The same binary gives the same bits on another x86-64 CPU (issue "Trustworthy numbers"): the
quick AN0 beam run three times: as the machine is (its widest SIMD level, AVX-512 here); as on an
older x86-64, with glibc told that the CPU lacks AVX2, FMA and AVX-512
(GLIBC_TUNABLES=glibc.cpu.hwcaps=-AVX2,-FMA,-AVX512F: libm's sin, cos, atan2 and pow take their
baseline code paths) and rcdem's two lane kernels on their baseline (SSE2) versions
(RCDEM_SIMD=baseline, core/simd_level.hpp); and with the kernels' AVX2 versions. The portable
build (no -march=native, no contraction; lane kernels that never sum across lanes) must give
byte-identical history.csv files. A native build is skipped (77): it is not meant to be
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
    for name, tunables, simd in (("as is", None, None), ("baseline libm", masked, "baseline"),
                                 ("avx2 kernels", None, "avx2")):
        env = dict(os.environ)
        if tunables:
            env["GLIBC_TUNABLES"] = tunables
        if simd:
            env["RCDEM_SIMD"] = simd
        out = os.path.join(tmp, name.replace(" ", "_"))
        r = subprocess.run([rcdem, "-q", "run", scenario, "-o", out], cwd=source, env=env,
                           capture_output=True, text=True, timeout=1200)
        check(r.returncode == 0, f"quick AN0 ({name}) exits 0 ({r.stderr.strip()[-300:]})")
        runs[name] = out
    def summary(name):
        path = os.path.join(runs[name], "summary.json")
        return json.load(open(path)) if os.path.exists(path) else {}

    levels = {n: summary(n).get("rcdem", {}).get("simd") for n in runs}
    check(levels["baseline libm"] == "baseline" and levels["avx2 kernels"] in ("avx2", "baseline"),
          f"summary.json names the SIMD level each ran at ({levels})")
    a = os.path.join(runs["as is"], "history.csv")
    for other in ("baseline libm", "avx2 kernels"):
        b = os.path.join(runs[other], "history.csv")
        same = os.path.exists(a) and os.path.exists(b) and filecmp.cmp(a, b, shallow=False)
        check(same, f"history.csv byte-identical: {other} ({levels[other]}) against as is "
              f"({levels['as is']}); peaks {summary(other).get('peak_load_N')!r} / "
              f"{summary('as is').get('peak_load_N')!r} N")
checks.finish()
