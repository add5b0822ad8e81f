#!/usr/bin/python3
"""Elastic E and nu of one uniaxial-compression run along z (e.g.
examples/uniaxial/cube160_elastic.toml): least-squares slopes of the stress (load over the loaded
area, summary.json gauges.face_area_m2) and of the lateral strains against the axial strain, over
the rows between 40% and 100% of the final load where the kinetic energy is below 5% of the
strain energy, for the interior gauge and for the face gauges.

usage: elastic_moduli.py RUN_DIR
"""
import csv
import json
import os
import sys

import numpy as np


def main(run):
    rows = list(csv.DictReader(open(os.path.join(run, "history.csv"))))
    summary = json.load(open(os.path.join(run, "summary.json")))
    area = float(np.mean(summary["gauges"]["face_area_m2"][4:6]))  # the z- and z+ faces

    def col(name):
        return np.array([float(r[name]) for r in rows])
    load, kinetic, strain = col("load_N"), col("kinetic_J"), col("strain_J")
    window = (load >= 0.4 * load[-1]) & (kinetic < 0.05 * np.maximum(strain, 1e-300))
    if window.sum() < 3:
        sys.exit(f"{run}: fewer than 3 quasi-static rows between 40% and 100% of the final load")
    stress = load[window] / area
    for label, prefix in (("interior gauge", "interior_strain_"), ("face gauges", "strain_")):
        ez = col(prefix + "z")[window]
        e_mod = -np.polyfit(ez, stress, 1)[0]
        nu = np.mean([-np.polyfit(ez, col(prefix + a)[window], 1)[0] for a in "xy"])
        print(f"{label}: E = {e_mod / 1e9:.2f} GPa, nu = {nu:.4f}")
    print(f"{window.sum()} rows, {load[window][0] / 1e3:.1f}-{load[window][-1] / 1e3:.1f} kN, "
          f"kinetic/strain <= {np.max(kinetic[window] / strain[window]):.2e}; rcdem "
          f"{summary.get('rcdem', {}).get('git_hash')}")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
