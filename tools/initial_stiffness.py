#!/usr/bin/python3
"""Initial stiffness K0 of one three-point bending run against the Timoshenko bracket, read as the
study's report reads it (tools/study_report.py: the slope between 10% and 40% of the load at the
first broken point, or of the largest load if none broke, over the quasi-static rows).

usage: initial_stiffness.py RUN_DIR MODEL      (MODEL: AN0 ... AN4, for the bars' section)
"""
import json
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import study_report as sr  # noqa: E402

run, model = sys.argv[1], sys.argv[2]
d, p = sr.curve(run)
s = json.load(open(os.path.join(run, "summary.json")))
first = s.get("first_cracking") or {}
k0, qs, ke, imb = sr.initial_stiffness(d, p, first.get("load_N"),
                                       *sr.energy_rows(run, p, sr.reactions(run)))
kt, _ = sr.timoshenko_stiffness(model)
kt_inner, _ = sr.timoshenko_stiffness(model, sr.SPAN - 0.020)
inside = k0 is not None and kt <= k0 <= kt_inner
print(f"{run}: K0 = {'–' if k0 is None else f'{k0 / 1e6:.1f}'} kN/mm "
      f"({'quasi-static rows' if qs else 'NOT quasi-static'}: kinetic/strain "
      f"{'–' if ke is None else f'{ke[0]:.4f}-{ke[1]:.4f}'}, plate/supports imbalance "
      f"{'–' if imb is None else f'{100 * imb:.1f}%'}); Timoshenko {kt / 1e6:.1f} (span 600 mm) / "
      f"{kt_inner / 1e6:.1f} kN/mm (580 mm): {'inside' if inside else 'OUTSIDE'} the bracket; "
      f"rcdem {s.get('rcdem', {}).get('git_hash')}, {s['steps']} steps, {np.max(p) / 1e3:.2f} kN at "
      f"{np.max(d) * 1e3:.3f} mm")
