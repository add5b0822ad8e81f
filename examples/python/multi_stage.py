#!/usr/bin/python3
"""A multi-stage test driven from Python (docs/python.md): a cube in compression is preloaded,
held, taken through three unload-reload cycles of growing amplitude, then loaded past its peak,
all by a callback that watches the stress and sets the loading plate's velocity. The run writes
the usual outputs (history.csv, summary.json, snapshots); this script writes stages.csv beside
them and prints each stage as it starts.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/multi_stage.py [--quick] [-o DIR]

--quick: a 50 mm cube (about 300 particles, seconds); without it the 160 mm cube of
examples/uniaxial/compression.toml (minutes).
"""
import argparse
import csv
import os

import rcdem

HERE = os.path.dirname(os.path.abspath(__file__))
MPA = 1e6


class Program:
    """Stages in order, each (name, velocity factor, done(sim, stage_start_step)): a stage sets the
    loading plate's velocity (factor x the scenario's speed, towards the cube when negative) when
    it starts, and ends when done() holds; the run stops after the last."""

    def __init__(self, stages, speed, area):
        self.stages, self.speed, self.area = stages, speed, area
        self.k, self.start, self.log, self.peak = -1, 0, [], 0.0

    def stress(self, sim):
        return sim.load / self.area

    def __call__(self, sim):
        self.peak = max(self.peak, self.stress(sim))
        if self.k >= 0 and not self.stages[self.k][2](self, sim):
            return True
        self.k += 1
        if self.k == len(self.stages):
            return False
        name, factor, _ = self.stages[self.k]
        sim.set_plate_velocity("top", factor * self.speed)
        self.start = sim.steps
        self.log.append((name, sim.steps, sim.time, sim.load, sim.displacement))
        print(f"{name:>8}: step {sim.steps:6d}, stress {self.stress(sim) / MPA:6.2f} MPa, "
              f"displacement {sim.displacement * 1e6:8.2f} um")
        return True


def stages():
    held = 300  # steps
    out = [("preload", -1.0, lambda p, s: p.stress(s) > 5 * MPA),
           ("hold", 0.0, lambda p, s: s.steps - p.start >= held)]
    for k, amplitude in enumerate((10, 20, 30)):
        out.append((f"load{k + 1}", -1.0, lambda p, s, a=amplitude: p.stress(s) > a * MPA))
        out.append((f"unload{k + 1}", 1.0, lambda p, s: p.stress(s) < 1 * MPA))
    # On past the largest cycle and the peak, until the stress has fallen to 80% of the peak.
    out.append(("final", -1.0, lambda p, s: s.displacement < p.log[-2][4]
                and p.stress(s) < 0.8 * p.peak))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("-o", "--output", default="results/python_multi_stage")
    args = ap.parse_args()
    rcdem.set_quiet(True)
    sc = rcdem.Scenario.load(os.path.join(HERE, "../uniaxial/compression.toml"))
    # The program ends the run; the scenario's own rules only guard it.
    sc.set("stop.load_drop", 0.0).set("stop.displacement", 0.01).set("stop.steps", 1_000_000)
    sc.set("output.snapshots", 3)
    if args.quick:
        sc.set("specimen.size", [0.05, 0.05, 0.05])
    size = sc.to_dict()["specimen"]["size"]
    sim = rcdem.Simulation(sc)
    program = Program(stages(), abs(sim.plates["top"]["velocity"]), size[0] * size[1])
    summary = sim.run(args.output, every=10, callback=program)
    with open(os.path.join(args.output, "stages.csv"), "w", newline="") as out:
        w = csv.writer(out)
        w.writerow(["stage", "step", "time_s", "load_N", "displacement_m"])
        w.writerows(program.log)
    print(f"stopped by {summary['stop_reason']} after {summary['steps']} steps; peak "
          f"{summary['peak_load_N'] / size[0] / size[1] / MPA:.1f} MPa; energy balance error "
          f"{summary['energy']['balance_error']:.2g}; outputs in {args.output}")


if __name__ == "__main__":
    main()
