#!/usr/bin/python3
"""A live load-displacement plot with matplotlib (docs/python.md): the run's callback adds a
point every few steps and redraws, in a window where there is a display, else into a PNG that is
rewritten as the run goes (watch it with any image viewer). The final figure is
load_displacement_live.png in the run's directory.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/live_plot.py [--quick] [-o DIR]
        [SCENARIO]

SCENARIO: any scenario with a load (default examples/uniaxial/tension.toml); --quick: a 50 mm
cube for the default scenario, or stop.displacement / 5 for another.
"""
import argparse
import os

import matplotlib

if not os.environ.get("DISPLAY"):
    matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import rcdem  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))


class LivePlot:
    """The callback: a point per call, the figure redrawn every `redraw` calls."""

    def __init__(self, png, redraw=20):
        self.png, self.redraw, self.calls = png, redraw, 0
        self.x, self.y = [], []
        self.fig, self.ax = plt.subplots(figsize=(6, 4))
        (self.line,) = self.ax.plot([], [], "-", lw=1.5)
        self.ax.set_xlabel("displacement (mm)")
        self.ax.set_ylabel("load (kN)")
        self.ax.grid(alpha=0.3)

    def __call__(self, sim):
        self.x.append(abs(sim.displacement) * 1e3)
        self.y.append(sim.load / 1e3)
        self.calls += 1
        if self.calls % self.redraw == 0:
            self.draw(sim)

    def draw(self, sim):
        self.line.set_data(self.x, self.y)
        self.ax.relim()
        self.ax.autoscale_view()
        self.ax.set_title(f"step {sim.steps}, t = {sim.time * 1e3:.3f} ms")
        if matplotlib.get_backend().lower() == "agg":
            self.fig.savefig(self.png, dpi=100)
        else:
            plt.pause(0.001)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scenario", nargs="?", default=os.path.join(HERE, "../uniaxial/tension.toml"))
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("-o", "--output", default="results/python_live_plot")
    args = ap.parse_args()
    rcdem.set_quiet(True)
    sc = rcdem.Scenario.load(args.scenario).set("output.snapshots", 0)
    if args.quick:
        if args.scenario.endswith("uniaxial/tension.toml"):
            sc.set("specimen.size", [0.05, 0.05, 0.05])
        else:
            sc.set("stop.displacement", sc.to_dict()["stop"]["displacement"] / 5)
    os.makedirs(args.output, exist_ok=True)
    png = os.path.join(args.output, "load_displacement_live.png")
    sim = rcdem.Simulation(sc)
    plot = LivePlot(png)
    summary = sim.run(args.output, every=10, callback=plot)
    plot.draw(sim)
    plot.fig.savefig(png, dpi=100)
    print(f"{summary['stop_reason']} after {summary['steps']} steps, peak "
          f"{summary['peak_load_N'] / 1e3:.2f} kN; {len(plot.x)} points in {png}")


if __name__ == "__main__":
    main()
