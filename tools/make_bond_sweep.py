#!/usr/bin/python3
"""Writes the AN4 bond-sweep scenarios (docs/case-study.md, "Bond sweep") from the study's own
AN4 NL-B scenarios, so that they differ from them only in the interface and the stop:
examples/three_point_bending/bond_sweep/NAME[_seed2].toml from study/quick/AN4_NL-B.toml (stopped
at 2 mm instead of 1.2 mm), and bond_sweep/full/AN4_NL-B_NAME.toml from study/AN4_NL-B.toml.
Run from the repository root after tools/make_tpb_scenarios.py: tools/make_bond_sweep.py
"""
import os

ROOT = "examples/three_point_bending"
OUT = os.path.join(ROOT, "bond_sweep")

# name: (interface, strength scale, energy scale, description)
QUICK = {
    "EL": ("EL", 1, 1, "elastic interface (EL)"),
    "NL-A": ("NL-A", 1, 1, "NL-A (the concrete's strengths)"),
    "NL-B": ("NL-B", 1, 1, "NL-B (strengths halved, SPEC 8)"),
    "NL-B_G0.5": ("NL-B", 1, 0.5, "NL-B with the fracture energies halved too"),
    "NL-B_s0.5": ("NL-B", 0.5, 1, "NL-B strengths x 0.5 (1/4 of the concrete's)"),
    "NL-B_s0.25": ("NL-B", 0.25, 1, "NL-B strengths x 0.25 (1/8 of the concrete's)"),
    "NL-B_s0.125": ("NL-B", 0.125, 1, "NL-B strengths x 0.125 (1/16 of the concrete's)"),
}
FULL = ("NL-B_G0.5", "NL-B_s0.25")


def replace_once(text, old, new):
    if text.count(old) < 1:
        raise SystemExit(f"make_bond_sweep.py: the template lacks {old!r}")
    return text.replace(old, new)


def variant(template, law, strength, energy):
    extra = "".join(f"{key} = {value:g}\n" for key, value in
                    (("interface_strength_scale", strength), ("interface_energy_scale", energy))
                    if value != 1)
    return replace_once(template, 'interface = "NL-B"\n', f'interface = "{law}"\n{extra}')


def write(path, header, body):
    lines = body.split("\n")
    lines[:2] = header
    with open(path, "w") as f:
        f.write("\n".join(lines))


quick = open(os.path.join(ROOT, "study/quick/AN4_NL-B.toml")).read()
# The committed sweep (docs/case-study.md, "Bond sweep") was written before the quick resolution
# had its own contact set and rate (2026-11-27); rerunning this writes the sweep on today's.
quick = replace_once(quick, 'include = ["../../../calibrated_contact_quick.toml"]',
                     'include = ["../../calibrated_contact_quick.toml"]')
quick = replace_once(quick, "displacement = 0.0012   # m of midspan deflection",
                     "displacement = 0.002   # m of midspan deflection")
source = ('# Written from ../study/quick/AN4_NL-B.toml, stop at 2 mm; SI units. '
          'docs/case-study.md, "Bond sweep".')
for name, (law, strength, energy, desc) in QUICK.items():
    body = variant(quick, law, strength, energy)
    write(os.path.join(OUT, f"{name}.toml"),
          [f"# Bond sweep on the quick AN4 beam (2Phi10) to 2 mm: {desc}.", source], body)
    write(os.path.join(OUT, f"{name}_seed2.toml"),
          [f"# Bond sweep on the quick AN4 beam (2Phi10) to 2 mm, generator seed 2: {desc}.", source],
          replace_once(body, "\nseed = 1\n", "\nseed = 2\n"))

full = open(os.path.join(ROOT, "study/AN4_NL-B.toml")).read()
full = replace_once(full, 'include = ["../../calibrated_contact.toml"]',
                    'include = ["../../../calibrated_contact.toml"]')
for name in FULL:
    law, strength, energy, desc = QUICK[name]
    write(os.path.join(OUT, "full", f"AN4_{name}.toml"),
          [f"# Bond sweep, full-size AN4 beam (2Phi10) to 2 mm: {desc}.",
           '# Written from ../../study/AN4_NL-B.toml; SI units. docs/case-study.md, "Bond sweep".'],
          variant(full, law, strength, energy))
