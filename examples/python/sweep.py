#!/usr/bin/python3
"""A parameter sweep from Python (docs/python.md): the direct tension cube of
examples/uniaxial/tension.toml run once per value of the contacts' tensile strength sigma_nt,
each run in its own directory, and a table of the peak stress and the strain at the peak written
as sweep.csv and sweep.md.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/sweep.py [--quick] [-o DIR]
        [--values 3e6,4.15e6,5.5e6]

--quick: a 50 mm cube (seconds per run); without it the 160 mm cube (minutes per run).
"""
import argparse
import csv
import os

import rcdem

HERE = os.path.dirname(os.path.abspath(__file__))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("-o", "--output", default="results/python_sweep")
    ap.add_argument("--values", default="3e6,4.15e6,5.5e6", help="sigma_nt values [Pa]")
    args = ap.parse_args()
    rcdem.set_quiet(True)
    rows = []
    for value in (float(v) for v in args.values.split(",")):
        sc = rcdem.Scenario.load(os.path.join(HERE, "../uniaxial/tension.toml"))
        sc.set("contact.sigma_nt", value).set("output.snapshots", 0)
        if args.quick:
            sc.set("specimen.size", [0.05, 0.05, 0.05])
        size = sc.to_dict()["specimen"]["size"]
        out = os.path.join(args.output, f"sigma_nt={value:g}")
        summary = rcdem.Simulation(sc).run(out)
        run = rcdem.load_run(out)
        rows.append({"sigma_nt_MPa": value / 1e6,
                     "peak_stress_MPa": summary["peak_load_N"] / (size[0] * size[1]) / 1e6,
                     "strain_at_peak": summary["displacement_at_peak_m"] / size[2],
                     "steps": summary["steps"], "stop_reason": summary["stop_reason"],
                     "history_rows": len(run.history), "directory": out})
        print(f"sigma_nt {value / 1e6:5.2f} MPa: peak {rows[-1]['peak_stress_MPa']:6.3f} MPa at "
              f"strain {rows[-1]['strain_at_peak']:.3e} ({summary['steps']} steps)")
    with open(os.path.join(args.output, "sweep.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    with open(os.path.join(args.output, "sweep.md"), "w") as f:
        f.write("| sigma_nt (MPa) | peak stress (MPa) | strain at peak | steps |\n|---|---|---|---|\n")
        for r in rows:
            f.write(f"| {r['sigma_nt_MPa']:.2f} | {r['peak_stress_MPa']:.3f} | "
                    f"{r['strain_at_peak']:.3e} | {r['steps']} |\n")
    print(f"table in {os.path.join(args.output, 'sweep.md')}")


if __name__ == "__main__":
    main()
