"""rcdem from Python (docs/python.md): scenarios with the CLI's checks, simulations stepped or run
with a callback, numpy views of their state, and readers for run and study directories.

    import rcdem
    sc = rcdem.Scenario.load("examples/three_point_bending/AN0_quick.toml")
    sc.set("stop.displacement", 2e-4)
    sim = rcdem.Simulation(sc)          # generates the specimen
    sim.step(100)
    print(sim.time, sim.load, sim.position[:3])
    summary = sim.run("results/py_run", every=50, callback=lambda s: s.load < 1e4)
    run = rcdem.load_run("results/py_run")
"""
import os

from ._rcdem import Error, _Scenario, _Simulation, run_directory_scenario, set_quiet
from ._toml import toml_document, toml_value
from ._files import Run, Study, load_run, load_study

__all__ = ["Error", "Scenario", "Simulation", "INTERRUPT", "load_run", "load_study", "Run",
           "Study", "set_quiet"]

# A run callback's return value that interrupts the run as SIGINT would: a checkpoint and the
# outputs so far are written, and `rcdem run --resume DIR` (or Simulation.resume) continues it.
INTERRUPT = "interrupt"


class Scenario:
    """A scenario, checked as the CLI checks it; an error raises rcdem.Error with its message."""

    def __init__(self, core):
        self._core = core

    @classmethod
    def load(cls, path):
        """The scenario file `path` (its includes found from its directory)."""
        return cls(_Scenario.load(os.fspath(path)))

    @classmethod
    def from_text(cls, text, source="scenario.toml"):
        """A scenario from TOML text; `source` names it in errors and locates its includes."""
        return cls(_Scenario.from_text(text, os.path.abspath(os.fspath(source))))

    @classmethod
    def from_dict(cls, d, source="scenario.toml"):
        """A scenario from nested dicts as the TOML file would hold them."""
        return cls.from_text(toml_document(d), source)

    def set(self, key, value):
        """Sets `key` (dotted, as --set) to `value` (a number, string, bool or list), checked as
        the CLI's --set; returns the scenario, so calls chain."""
        self._core.set_toml(key, toml_value(value))
        return self

    def to_toml(self):
        """The scenario's text, with the keys set on it written in."""
        return self._core.to_toml()

    def to_dict(self):
        """The scenario's own text as dicts (the files it includes are not merged in)."""
        import tomllib
        return tomllib.loads(self.to_toml())

    @property
    def source(self):
        return self._core.source

    @property
    def set_keys(self):
        """The KEY=VALUE items set on it, in order."""
        return self._core.set_keys

    def __repr__(self):
        return f"rcdem.Scenario({str(self.source)!r}, set={self.set_keys})"


class Simulation(_Simulation):
    """A specimen generated from a scenario and its solver (docs/python.md).

    State as numpy views without copies, valid while the simulation lives and re-read after
    every step (the arrays do not move): position, position0, velocity (writable),
    angular_velocity, orientation (x, y, z, w), force, torque, mass, radius per body (the concrete
    particles first, then the bars' cylinders); point_damage per concrete local point (read-only,
    strided into the point records), point_opening (its accumulated normal displacement, m,
    opening positive); contact_force per contact, node_axial_force per bar node.
    Copies: contact_particles. Dicts built on each read: energies, gauges, plates.
    """

    def __init__(self, scenario):
        if not isinstance(scenario, Scenario):
            scenario = Scenario.load(scenario)
        super().__init__(scenario._core)
        self.scenario = scenario
        self._resume_dir = None

    @classmethod
    def resume(cls, directory):
        """The interrupted run in `directory`, to continue with .run() (no `out`): its scenario as
        run, its state restored from its newest checkpoint when the run continues."""
        sim = cls(Scenario(run_directory_scenario(os.fspath(directory))))
        sim._resume_dir = os.fspath(directory)
        return sim

    def run(self, out=None, every=1, callback=None, checkpoint_every=0, until=None):
        """Runs to the scenario's stop rules as `rcdem run` does, writing its outputs into `out`
        (history.csv, summary.json, snapshots, ...); returns summary.json as a dict.

        callback(sim), every `every` steps after the step's outputs and stop rules, may read and
        change the simulation (set_plate_velocity) and returns None or True to go on, False to
        stop the run (stop_reason "callback"), or rcdem.INTERRUPT to interrupt it resumably.
        checkpoint_every: a checkpoint every that many steps (0: only on an interrupt).
        until: the run also ends (stop_reason "until") at this step (an int) or simulation
        time (a float, s), whichever of it and the scenario's stop rules comes first."""
        resume = False
        if out is None:
            if self._resume_dir is None:
                raise Error("run: no output directory given (out=...)")
            out, resume = self._resume_dir, True
            self._resume_dir = None
        return super().run(os.fspath(out), every, callback, checkpoint_every, resume, until)

    def __repr__(self):
        return (f"rcdem.Simulation({self.body_count} bodies, step {self.steps}, "
                f"t = {self.time:.6g} s)")
