#!/usr/bin/python3
"""The Debian package (issue 45, item 4): `cpack -G DEB` in the build directory gives
rcdem_<version>_<arch>.deb, which, unpacked into a clean root (dpkg-deb -x: what `apt install`
puts on a machine, without installing it here):

  * declares the Python packages its tools need beside the shared libraries;
  * holds the binary, its tools, the examples, the docs and a man page with every command;
  * runs from there in a clean directory: `--version`, a short run of a packaged example whose
    plot is drawn by the packaged tool, and a built-in study found among the packaged examples;
  * `import rcdem` from its Python package steps a packaged example.

usage: check_package.py RCDEM_BINARY SOURCE_DIR BUILD_DIR
"""
import glob
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checklist import Checklist  # noqa: E402

rcdem, source, build = (os.path.abspath(a) for a in sys.argv[1:4])
checks = Checklist()
check = checks.check

with tempfile.TemporaryDirectory() as tmp:
    r = subprocess.run(["cpack", "-G", "DEB", "-B", os.path.join(tmp, "pkg"), "--config",
                        os.path.join(build, "CPackConfig.cmake")], capture_output=True, text=True,
                       timeout=600)
    debs = glob.glob(os.path.join(tmp, "pkg", "rcdem_*.deb"))
    check(r.returncode == 0 and len(debs) == 1, f"cpack makes one .deb ({r.stderr.strip()[-200:]})")
    if not debs:
        checks.finish()
    info = subprocess.run(["dpkg-deb", "-I", debs[0]], capture_output=True, text=True).stdout
    depends = next((x for x in info.splitlines() if x.strip().startswith("Depends:")), "")
    check(all(p in depends for p in ("python3-matplotlib", "python3-numpy", "libvoro++1",
                                     "libtomlplusplus3")),
          f"it depends on the tools' Python packages and the libraries ({depends.strip()[:160]})")
    root = os.path.join(tmp, "root")
    subprocess.run(["dpkg-deb", "-x", debs[0], root], check=True)
    exe = os.path.join(root, "usr/bin/rcdem")
    share = os.path.join(root, "usr/share/rcdem")
    man = os.path.join(root, "usr/share/man/man1/rcdem.1")
    check(os.access(exe, os.X_OK) and os.path.exists(os.path.join(share, "tools/plot_history.py"))
          and os.path.exists(os.path.join(share, "examples/uniaxial/compression.toml"))
          and os.path.exists(os.path.join(root, "usr/share/doc/rcdem/README.md"))
          and os.path.exists(os.path.join(root, "usr/share/doc/rcdem/outputs.md")),
          "the binary, tools, examples and docs are in the package")
    page = open(man).read() if os.path.exists(man) else ""
    check(all(f'.SS "rcdem {c}"' in page for c in ("generate", "run", "calibrate", "study"))
          and "--set" in page.replace("\\-", "-"),
          "the man page documents every command and its options")
    work = os.path.join(tmp, "clean")
    os.makedirs(work)
    v = subprocess.run([exe, "--version"], capture_output=True, text=True, cwd=work)
    check(v.returncode == 0 and v.stdout.startswith("rcdem "), f"--version: {v.stdout.strip()}")
    r = subprocess.run([exe, "-q", "run", os.path.join(share, "examples/uniaxial/compression.toml"),
                        "-o", "out", "--set", "stop.steps=200"], capture_output=True, text=True,
                       cwd=work, timeout=600)
    check(r.returncode == 0 and os.path.exists(os.path.join(work, "out/summary.json"))
          and os.path.exists(os.path.join(work, "out/load_displacement.png")),
          f"a packaged example runs in a clean directory, its plot drawn ({r.stderr.strip()[-200:]})")
    r = subprocess.run([exe, "study", "three_point_bending", "--quick", "--cases", "none"],
                       capture_output=True, text=True, cwd=work)
    check(r.returncode == 1 and os.path.join(share, "examples/three_point_bending/study/quick")
          in r.stderr, "the built-in study's scenarios are the packaged ones")
    # `import rcdem` from the package alone (not the build tree), in a clean directory.
    site = os.path.join(root, "usr/lib/python3/dist-packages")
    code = ("import rcdem, sys; sc = rcdem.Scenario.load(sys.argv[1]).set('stop.steps', 50); "
            "sim = rcdem.Simulation(sc); sim.step(50); print(rcdem.__file__, sim.steps)")
    r = subprocess.run(["/usr/bin/python3", "-c", code,
                        os.path.join(share, "examples/uniaxial/compression.toml")],
                       capture_output=True, text=True, cwd=work, timeout=600,
                       env=dict(os.environ, PYTHONPATH=site))
    check(r.returncode == 0 and r.stdout.startswith(site) and r.stdout.split()[-1] == "50",
          f"import rcdem from the package steps a packaged example ({(r.stdout + r.stderr)[-200:]})")

checks.finish()
