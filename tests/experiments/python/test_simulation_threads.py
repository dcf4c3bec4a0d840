"""Long calls release the GIL (another Python thread runs while advance steps) and stop on
Ctrl-C between two steps, the state whole (docs/python.md)."""
import os
import signal
import subprocess
import sys
import threading

import numpy as np

import drapelab
from conftest import SCENES, child_env, scene


def interrupt_after_start(script, started, wait):
    """Runs script in a child Python, sends it Ctrl-C `wait` seconds after it printed `started`,
    and checks that it caught KeyboardInterrupt (printed "interrupted") and exited 0."""
    child = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, text=True, env=child_env())
    assert child.stdout.readline().strip() == started
    threading.Event().wait(wait)
    child.send_signal(signal.SIGINT)
    out, err = child.communicate(timeout=60)
    assert child.returncode == 0, err
    assert out.strip() == "interrupted"


def test_another_thread_runs_while_advance_steps():
    sim = drapelab.Simulation(scene("fig2_hold.json", duration=2.5))
    advancing = [False]
    seen = []

    def work():
        total = 0
        for i in range(20000):
            total += i
        seen.append((advancing[0], sim.time, total))

    advancing[0] = True
    worker = threading.Thread(target=work)
    worker.start()
    sim.advance(2.5)
    advancing[0] = False
    worker.join()
    # The worker finished its loop while the advance stepped (it read a time inside the run).
    assert seen[0][0] is True
    assert 0.0 <= seen[0][1] < 2.5
    assert seen[0][2] == 20000 * 19999 // 2
    assert sim.time == 2.5


def test_ctrl_c_stops_advance_between_steps(tmp_path):
    script = f"""
import math, sys, numpy as np, drapelab
sim = drapelab.Simulation(drapelab.load_scene({str(SCENES / "fig2_hold.json")!r},
                                              overrides={{"duration": 600}}))
print("stepping", flush=True)
try:
    sim.advance(600)
except KeyboardInterrupt:
    t = sim.time
    assert 0 < t < 600 and np.isfinite(sim.positions).all()
    assert sim.step() is True and sim.time > t  # it goes on from where it stopped
    print("interrupted", flush=True)
"""
    interrupt_after_start(script, "stepping", 0.3)


def test_ctrl_c_stops_run_and_leaves_the_folder_unfinished(tmp_path):
    out = tmp_path / "run"
    script = f"""
import numpy as np, drapelab
sim = drapelab.Simulation(drapelab.load_scene({str(SCENES / "fig2_hold.json")!r},
                                              overrides={{"duration": 600}}))
print("running", flush=True)
try:
    sim.run({str(out)!r})
except KeyboardInterrupt:
    assert 0 < sim.time < 600 and np.isfinite(sim.positions).all()
    print("interrupted", flush=True)
"""
    interrupt_after_start(script, "running", 0.5)
    # The folder was written up to the stop and is visibly unfinished: no summary.json.
    assert (out / "energy.csv").exists()
    assert not (out / "summary.json").exists()
    assert not (out / "state.csv").exists()
