"""Fixtures for the Python API's tests (docs/python.md). Run by ctest as python.pytest with
PYTHONPATH at the build's python/ folder, RCDEM_BINARY and RCDEM_SOURCE_DIR set."""
import os
import subprocess

import pytest

import rcdem

SOURCE = os.environ.get("RCDEM_SOURCE_DIR",
                        os.path.dirname(os.path.dirname(os.path.dirname(__file__))))
BINARY = os.environ.get("RCDEM_BINARY", os.path.join(SOURCE, "build", "rcdem"))
SMALL = os.path.join(SOURCE, "tests", "regression", "small_run.toml")

rcdem.set_quiet(True)


@pytest.fixture
def small():
    """A 50 mm cube with a bar, compressed: 314 bodies, a run of a few hundred steps in a second."""
    return rcdem.Scenario.load(SMALL).set("stop.steps", 400).set("output.snapshots", 2)


def cli(*args, check=True):
    """`rcdem ARGS` quietly; the completed process."""
    r = subprocess.run([BINARY, "-q", *args], capture_output=True, text=True, timeout=600)
    if check and r.returncode != 0:
        raise AssertionError(f"rcdem {' '.join(args)}: exit {r.returncode}: {r.stderr}")
    return r


def read(path):
    with open(path, "rb") as f:
        return f.read()
