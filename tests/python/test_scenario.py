"""rcdem.Scenario: loading, keys set with the CLI's checks and messages, TOML text and dicts."""
import tomllib

import numpy as np
import pytest

import rcdem
from conftest import SMALL, cli


def test_load_names_the_file(small):
    assert str(small.source).endswith("small_run.toml")
    assert small.set_keys == ["stop.steps=400", "output.snapshots=2"]


def test_set_writes_the_value_into_the_text(small):
    small.set("solver.damping", 0.25)
    assert tomllib.loads(small.to_toml())["solver"]["damping"] == 0.25
    assert small.to_dict()["stop"]["steps"] == 400


def test_a_bad_value_raises_the_clis_message(small):
    with pytest.raises(rcdem.Error) as e:
        small.set("solver.damping", 7)
    r = cli("run", SMALL, "-o", "/nonexistent/never", "--set", "solver.damping=7", check=False)
    assert r.returncode != 0
    assert str(e.value) == r.stderr.strip().removeprefix("rcdem: error: ")
    assert "expected a number in [0, 1), got 7" in str(e.value)


def test_an_unknown_key_is_named(small):
    with pytest.raises(rcdem.Error, match="unknown key 'solver.dampingg'"):
        small.set("solver.dampingg", 0.1)


def test_a_failed_set_leaves_the_scenario_as_it_was(small):
    before = small.to_toml()
    with pytest.raises(rcdem.Error):
        small.set("specimen.shape", "teapot")
    assert small.to_toml() == before


def test_values_of_every_kind_become_toml():
    from rcdem._toml import toml_value
    assert toml_value(True) == "true"
    assert toml_value(3) == "3"
    assert toml_value(0.1) == "0.1"
    assert toml_value("beam") == '"beam"'
    assert toml_value([0.7, 0.15, 0.1]) == "[0.7, 0.15, 0.1]"
    assert toml_value(np.float64(2.5)) == "2.5"
    assert toml_value(np.array([1.0, 2.0])) == "[1.0, 2.0]"
    with pytest.raises(ValueError):
        toml_value(float("nan"))
    with pytest.raises(TypeError):
        toml_value(object())


def test_from_dict_is_the_file():
    with open(SMALL, "rb") as f:
        d = tomllib.load(f)
    a = rcdem.Simulation(rcdem.Scenario.from_dict(d, source=SMALL))
    b = rcdem.Simulation(rcdem.Scenario.load(SMALL))
    assert a.time_step == b.time_step
    assert np.array_equal(a.position, b.position)


def test_bad_toml_text_names_its_source():
    with pytest.raises(rcdem.Error, match="mine.toml"):
        rcdem.Scenario.from_text("[specimen\nshape = 1\n", source="mine.toml")
