"""tests/regression/small_run.toml stopped by SIGINT after its checkpoints (every 200 steps), for
the scripts that damage or inspect what an interrupted run leaves."""
import glob
import os
import signal
import subprocess
import time


def checkpoints(d):
    return sorted(glob.glob(os.path.join(d, "checkpoint_*.h5")))


def interrupted_run(rcdem, scenario_text, tmp, name, min_step=0):
    """The run of `scenario_text` in tmp/name stopped by SIGINT once it has two checkpoints, the
    newest at step `min_step` or later; returns (directory, scenario file)."""
    scenario = os.path.join(tmp, name + ".toml")
    open(scenario, "w").write(scenario_text)
    d = os.path.join(tmp, name)
    p = subprocess.Popen([rcdem, "-q", "run", scenario, "-o", d, "--checkpoint-every", "200"],
                         stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    t0 = time.time()
    while p.poll() is None and time.time() - t0 < 120:
        found = checkpoints(d) if os.path.isdir(d) else []
        if len(found) >= 2 and int(os.path.basename(found[-1])[11:23]) >= min_step:
            p.send_signal(signal.SIGINT)
            break
        time.sleep(0.01)
    p.wait(timeout=120)
    assert len(checkpoints(d)) >= 2 and not os.path.exists(os.path.join(d, "summary.json")), d
    return d, scenario
