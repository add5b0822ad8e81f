"""Simulation.run: the CLI's run loop and outputs, driven and stopped from Python; resuming."""
import os

import numpy as np
import pytest

import rcdem
from conftest import SMALL, cli, read


def test_history_is_byte_identical_to_the_clis(small, tmp_path):
    cli("run", SMALL, "-o", str(tmp_path / "cli"), "--set", "stop.steps=400", "--set",
        "output.snapshots=2")
    summary = rcdem.Simulation(small).run(tmp_path / "py")
    assert summary["stop_reason"] == "steps" and summary["steps"] == 400
    for name in ("history.csv", "broken_points.csv", "scenario.toml"):
        assert read(tmp_path / "py" / name) == read(tmp_path / "cli" / name), name


def test_a_callback_stops_the_run(small, tmp_path):
    seen = []

    def callback(sim):
        seen.append(sim.steps)
        return sim.steps < 200

    summary = rcdem.Simulation(small).run(tmp_path / "run", every=50, callback=callback)
    assert seen == [50, 100, 150, 200]
    assert summary["stop_reason"] == "callback"
    assert summary["steps"] == 200
    history = rcdem.load_run(tmp_path / "run").history
    assert history["step"][-1] == 200


def held_run(scenario, out, at, stop, read, **run):
    """A run whose callback (every 100 steps) calls stop(sim) at step `at` and records read(sim)
    at every later call; the summary and {step: read(sim)}."""
    held = {}

    def hold(sim):
        if sim.steps == at:
            stop(sim)
        if sim.steps > at:
            held[sim.steps] = read(sim)

    return rcdem.Simulation(scenario).run(out, every=100, callback=hold, **run), held


def test_a_callback_changes_the_loading(small, tmp_path):
    _, held = held_run(small, tmp_path / "run", 100, lambda s: s.set_plate_velocity("top", 0.0),
                       lambda s: s.plates["top"]["displacement"])
    assert held[200] == held[300] < 0  # the plate stopped where it was (400 ends the run)


def test_a_bad_callback_return_is_an_error(small, tmp_path):
    with pytest.raises(rcdem.Error, match="expected None, True, False or rcdem.INTERRUPT"):
        rcdem.Simulation(small).run(tmp_path / "run", every=10, callback=lambda s: "later")


def test_an_exception_in_the_callback_reaches_the_caller(small, tmp_path):
    def boom(sim):
        raise KeyError("from the callback")

    with pytest.raises(KeyError, match="from the callback"):
        rcdem.Simulation(small).run(tmp_path / "run", every=10, callback=boom)


def test_interrupted_from_python_resumed_by_the_cli_bitwise(small, tmp_path):
    cli("run", SMALL, "-o", str(tmp_path / "whole"), "--set", "stop.steps=400", "--set",
        "output.snapshots=2")
    part = tmp_path / "part"
    summary = rcdem.Simulation(small).run(
        part, every=150, callback=lambda s: rcdem.INTERRUPT if s.steps == 150 else None)
    assert summary["stop_reason"] == "interrupted"
    assert any(n.startswith("checkpoint_") for n in os.listdir(part))
    cli("run", "--resume", str(part))
    for name in ("history.csv", "broken_points.csv"):
        assert read(part / name) == read(tmp_path / "whole" / name), name


def test_resumed_in_python(small, tmp_path):
    whole = rcdem.Simulation(small).run(tmp_path / "whole")
    part = tmp_path / "part"
    rcdem.Simulation(small).run(part, every=100, callback=lambda s: rcdem.INTERRUPT)
    sim = rcdem.Simulation.resume(part)
    summary = sim.run()
    assert summary["steps"] == whole["steps"] == 400
    assert read(part / "history.csv") == read(tmp_path / "whole" / "history.csv")


def test_run_needs_a_directory(small):
    with pytest.raises(rcdem.Error, match="no output directory"):
        rcdem.Simulation(small).run()


def test_load_run_reads_every_output(small, tmp_path):
    rcdem.Simulation(small).run(tmp_path / "run")
    run = rcdem.load_run(tmp_path / "run")
    assert run.summary["steps"] == 400
    assert "load_N" in run.columns and run.history.dtype["load_N"] == np.float64
    assert run.history["step"][-1] == 400
    assert len(run.snapshots["particles"]) >= 2
    assert all(os.path.exists(p) for p in run.snapshots["bars"])
    assert run.manifest["exit_state"] == "finished"
    with pytest.raises(FileNotFoundError):
        rcdem.load_run(tmp_path)


def test_load_study(tmp_path):
    cases = tmp_path / "cases"
    cases.mkdir()
    (cases / "cube.toml").write_text(open(SMALL).read())
    cli("study", "cube", "--scenarios", str(cases), "-o", str(tmp_path / "study"), "--set",
        "stop.steps=200", "--sweep", "solver.damping=0.1,0.2", "-j", "1")
    study = rcdem.load_study(tmp_path / "study")
    assert len(study.runs) == 2
    assert len(study.peak_loads) == 2
    assert {r["directory"] for r in study.peak_loads} == {"cube_damping=0.1", "cube_damping=0.2"}
    assert set(study.runs) == {"cases/cube_damping=0.1", "cases/cube_damping=0.2"}


def test_until_a_step_or_a_time(small, tmp_path):
    s = rcdem.Simulation(small).run(tmp_path / "steps", until=123)
    assert s["stop_reason"] == "until" and s["steps"] == 123
    sim = rcdem.Simulation(small)
    t_end = 50.5 * sim.time_step
    s = sim.run(tmp_path / "time", until=t_end, every=7, callback=lambda x: None)
    assert s["stop_reason"] == "until" and s["steps"] == 51  # the first step at or past it
    with pytest.raises(rcdem.Error, match="until"):
        rcdem.Simulation(small).run(tmp_path / "bad", until=-1)


def test_a_callback_holds_a_pulled_bar(tmp_path):
    from conftest import SOURCE
    sc = rcdem.Scenario.load(os.path.join(SOURCE, "examples", "pull_out", "NL-B.toml"))
    sc.set("output.snapshots", 0)
    s, held = held_run(sc, tmp_path / "run", 600, lambda s: s.set_pull_velocity("bar", 0.0),
                       lambda s: s.pulled_bars["bar"]["displacement"], until=900)
    assert s["stop_reason"] == "until"
    assert held[700] == held[800] > 0  # the bar stopped where it was
    with pytest.raises(rcdem.Error, match="no pulled bar 'rod'"):
        rcdem.Simulation(sc).set_pull_velocity("rod", 0.0)
