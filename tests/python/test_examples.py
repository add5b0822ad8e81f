"""examples/python at their quick size: each runs and writes what it promises."""
import csv
import os
import subprocess
import sys

from conftest import SOURCE

EXAMPLES = os.path.join(SOURCE, "examples", "python")


def example(name, out, *args):
    r = subprocess.run([sys.executable, os.path.join(EXAMPLES, name), "--quick", "-o", str(out),
                        *args], capture_output=True, text=True, timeout=600,
                       env=dict(os.environ, DISPLAY=""))
    assert r.returncode == 0, r.stderr[-500:]
    return r.stdout


def test_multi_stage(tmp_path):
    example("multi_stage.py", tmp_path)
    stages = list(csv.DictReader(open(tmp_path / "stages.csv")))
    names = [s["stage"] for s in stages]
    assert names == ["preload", "hold", "load1", "unload1", "load2", "unload2", "load3",
                     "unload3", "final"]
    load = {s["stage"]: float(s["load_N"]) for s in stages}
    area = 0.05 * 0.05
    for k, amplitude in enumerate((10e6, 20e6, 30e6)):  # each cycle reached, then unloaded
        assert load[f"unload{k + 1}"] >= amplitude * area
        assert load[f"load{k + 2}" if k < 2 else "final"] <= 1e6 * area
    assert os.path.exists(tmp_path / "history.csv")


def test_sweep(tmp_path):
    example("sweep.py", tmp_path, "--values", "3e6,5.5e6")
    rows = list(csv.DictReader(open(tmp_path / "sweep.csv")))
    assert [float(r["sigma_nt_MPa"]) for r in rows] == [3.0, 5.5]
    assert all(r["stop_reason"] in ("load_drop", "displacement") for r in rows)
    assert float(rows[1]["peak_stress_MPa"]) > float(rows[0]["peak_stress_MPa"])
    assert (tmp_path / "sweep.md").read_text().count("\n") == 4


def test_live_plot(tmp_path):
    out = example("live_plot.py", tmp_path)
    assert "points in" in out
    assert (tmp_path / "load_displacement_live.png").stat().st_size > 10_000
