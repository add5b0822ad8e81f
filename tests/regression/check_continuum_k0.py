#!/usr/bin/python3
"""tools/continuum_beam_k0.py (the continuum measure of a beam's initial stiffness) against
beam theory where beam theory holds: a slender beam (span 2 m, depth 0.1 m, 4 mm plates) within
1.5% of Timoshenko's P/delta on the coarsest mesh; K proportional to E; glued plates stiffer than
frictionless ones; the study's AN0 beam inside the Timoshenko bracket of its 600 / 580 mm spans
(Timoshenko as the study's report computes it, tools/study_report.py)."""
import os
import sys

sys.path.insert(0, os.path.join(sys.argv[1], "tools"))
import continuum_beam_k0 as fe  # noqa: E402


def stiffness(argv):
    a = fe.parser().parse_args(argv)
    return fe.solve(fe.Beam(a, 1), fe.elasticity(a.E, a.nu), a.plates == "glued")[0]


def timoshenko(span):
    return fe.sr.timoshenko_stiffness("AN0", span)[0]


failures = []
slender = ["--span", "2.0", "--length", "2.1", "--plate-width", "0.004"]
k = stiffness(slender)
if abs(k / timoshenko(2.0) - 1) > 0.015:
    failures.append(f"slender beam: {k:.6g} N/m against Timoshenko {timoshenko(2.0):.6g}")
k2 = stiffness(slender + ["--E", str(2 * fe.sr.E_CONCRETE)])
if abs(k2 / (2 * k) - 1) > 1e-9:
    failures.append(f"K not proportional to E: {k2:.9g} against 2 x {k:.9g}")
deep, glued = stiffness([]), stiffness(["--plates", "glued"])
if not glued > deep:
    failures.append(f"glued plates {glued:.6g} not stiffer than frictionless {deep:.6g}")
if not timoshenko(0.600) <= deep <= timoshenko(0.580):
    failures.append(f"AN0 beam {deep:.6g} outside Timoshenko's {timoshenko(0.6):.6g} / "
                    f"{timoshenko(0.58):.6g}")
print("\n".join(failures) or f"ok: slender {k / timoshenko(2.0):.4f} of Timoshenko, AN0 beam "
      f"{deep / 1e6:.2f} kN/mm (glued {glued / 1e6:.2f})")
sys.exit(1 if failures else 0)
