#!/usr/bin/python3
"""The numbers docs/model.md quotes from single runs, printed from their directories, so that they
are regenerated rather than edited by hand (tools/regenerate_docs.sh runs the runs).

usage:
  docs_numbers.py counts GENERATE_DIR    particles, contacts and local points of a specimen
  docs_numbers.py stirrups RUN_DIR       examples/stirrups/beam.toml: stirrup and tie forces
  docs_numbers.py probe RUN_DIR          a short run's specimen, time step, set-up and step times
"""
import csv
import json
import os
import sys


def summary(d):
    with open(os.path.join(d, "summary.json")) as f:
        return json.load(f)


def rows(d):
    with open(os.path.join(d, "history.csv")) as f:
        return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]


def counts(d):
    s = summary(d)
    spec = s.get("specimen", s)
    p = spec["particles"]
    print(f"aggregate particles {p['aggregate']:,}; mortar particles {p['mortar']:,}; "
          f"steel interface spheres {p['steel']:,}; contacts {spec['contacts']:,}; "
          f"contacts per particle {spec['contacts_per_particle']:.2f}; "
          f"local points per contact {spec['local_points_per_contact']:.2f}")


STIRRUPS = ["stirrup_l1", "stirrup_l2", "stirrup_l3", "stirrup_r1", "stirrup_r2", "stirrup_r3"]


def stirrups(d):
    s, h = summary(d), rows(d)
    first = (s.get("first_cracking") or {}).get("step")
    intact = [x for x in h if first is None or x["step"] < first]
    end = h[-1]
    force = {n: end[f"{n}_max_axial_force_N"] for n in STIRRUPS}
    before = max(x[f"{n}_max_axial_force_N"] for x in intact for n in STIRRUPS)
    print("stirrup forces at the end (N): " +
          ", ".join(f"{n} {force[n]:.0f}" for n in STIRRUPS))
    print(f"largest stirrup force before the first broken point: {before:.0f} N")
    print(f"ties: {end['max_tie_force_N']:.0f} N at the end, "
          f"{max(x['max_tie_force_N'] for x in intact):.0f} N before the first broken point; "
          f"{s['specimen'].get('bar_ties')} ties")
    print(f"peak {s['peak_load_N'] / 1e3:.1f} kN; energy balance "
          f"{100 * s['energy']['balance_error']:.3f}%; {s['steps']:,} steps to "
          f"{1e3 * s['displacement_at_peak_m']:.3f} mm at the peak; {s['seconds']:.0f} s; "
          f"rcdem {s['rcdem']['git_hash']}")


def probe(d):
    s = summary(d)
    spec, p = s["specimen"], s["specimen"]["particles"]
    print(f"particles {p['total']:,} ({p['aggregate']:,} aggregate, {p['mortar']:,} mortar, "
          f"{p['steel']:,} interface spheres of {spec['bars']} bars), {spec['cylinders']:,} "
          f"cylinders; contacts {spec['contacts']:,}; local points {spec['local_points']:,}")
    threads = s["threads"].get("max", "?")
    print(f"time step {s['time_step_s']:.3g} s; {s['steps']:,} steps in {s['loop_seconds']:.1f} s "
          f"({s['steps_per_second']:.2f} steps/s, up to {threads} threads); set-up "
          f"{s['seconds'] - s['loop_seconds']:.0f} s; rcdem {s['rcdem']['git_hash']}")


def main(argv):
    commands = {"counts": counts, "stirrups": stirrups, "probe": probe}
    if len(argv) != 2 or argv[0] not in commands:
        sys.exit(__doc__)
    commands[argv[0]](argv[1])


if __name__ == "__main__":
    main(sys.argv[1:])
