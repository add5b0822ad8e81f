"""Readers for what `rcdem run` and `rcdem study` write (docs/outputs.md)."""
import csv
import json
import os
import re

import numpy as np


class Run:
    """A run directory: history (numpy structured array, one field per history.csv column),
    summary (summary.json as a dict), manifest, snapshots (per kind, the VTU paths in order)."""

    def __init__(self, directory):
        self.directory = os.fspath(directory)
        path = os.path.join(self.directory, "history.csv")
        if not os.path.exists(path):
            raise FileNotFoundError(f"{self.directory}: no history.csv (not a run directory)")
        self.history = np.genfromtxt(path, delimiter=",", names=True, deletechars="",
                                     ndmin=1)
        self.summary = self._json("summary.json")
        self.manifest = self._json("manifest.json")
        self.snapshots = {}
        for name in sorted(os.listdir(self.directory)):
            if name.endswith(".pvd"):
                text = open(os.path.join(self.directory, name), encoding="utf-8").read()
                self.snapshots[name[:-4]] = [os.path.join(self.directory, f)
                                             for f in re.findall(r'file="([^"]+)"', text)]

    def _json(self, name):
        path = os.path.join(self.directory, name)
        return json.load(open(path, encoding="utf-8")) if os.path.exists(path) else None

    @property
    def columns(self):
        return list(self.history.dtype.names)

    def __repr__(self):
        return f"rcdem.Run({self.directory!r}, {len(self.history)} history rows)"


class Study:
    """A study directory: peak_loads and cases (peak_loads.csv and cases.csv as lists of dicts)
    and its runs (name -> Run, for every run directory holding a history)."""

    def __init__(self, directory):
        self.directory = os.fspath(directory)
        self.peak_loads = self._csv("peak_loads.csv")
        self.cases = self._csv("cases.csv")
        self.runs = {}
        for root, dirs, files in os.walk(self.directory):
            dirs.sort()
            if "history.csv" in files and "summary.json" in files:
                self.runs[os.path.relpath(root, self.directory)] = Run(root)
        if not self.runs and self.peak_loads is None:
            raise FileNotFoundError(f"{self.directory}: no runs and no peak_loads.csv "
                                    "(not a study directory)")

    def _csv(self, name):
        path = os.path.join(self.directory, name)
        if not os.path.exists(path):
            return None
        with open(path, newline="", encoding="utf-8") as f:
            return list(csv.DictReader(f))

    def __repr__(self):
        return f"rcdem.Study({self.directory!r}, {len(self.runs)} runs)"


def load_run(directory):
    return Run(directory)


def load_study(directory):
    return Study(directory)
