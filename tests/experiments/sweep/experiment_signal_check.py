"""An experiment killed by its process id takes its runs with it (docs/experiments.md, "Resume").

`drapelab experiment` runs each run in a child process. Sent SIGTERM or SIGINT by its process
id alone (not to the terminal's process group, as Ctrl-C is), a parent that exited would leave
its children running to the end of their runs, and a resume started meanwhile would write the
same run folders at once. Each child dies with its parent, and a resume then finishes the plan.
Usage: experiment_signal_check.py DRAPELAB SOURCE_DIR WORK_DIR
"""
import json
import os
import pathlib
import shutil
import signal
import subprocess
import sys
import time


def children(pid):
    found = subprocess.run(["pgrep", "-P", str(pid)], capture_output=True, text=True).stdout
    return [int(k) for k in found.split()]


def alive(pid):
    try:
        with open(f"/proc/{pid}/stat") as stat:
            return stat.read().split()[2] != "Z"
    except FileNotFoundError:
        return False


def main():
    drapelab, source, work = sys.argv[1], pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3])
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    # Two runs of a minute or so each (leapfrog at 1e-6 s over 60 s of the 12 x 12 hold scene).
    definition = work / "long_runs.json"
    definition.write_text(json.dumps({
        "name": "long-runs", "scenes": [str(source / "experiments/scenes/fig2_hold.json")],
        "duration": 60, "sweep": {"integrator.dt": [1e-6, 1.1e-6]}}))
    for sig in (signal.SIGTERM, signal.SIGINT):
        out = work / sig.name
        parent = subprocess.Popen([drapelab, "experiment", definition, "--out", out, "-j", "2"],
                                  stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        deadline = time.monotonic() + 30
        kids = []
        while not kids and time.monotonic() < deadline:
            time.sleep(0.1)
            kids = children(parent.pid)
        assert kids, "no run started"
        parent.send_signal(sig)
        parent.wait(timeout=30)
        deadline = time.monotonic() + 5
        while any(alive(k) for k in kids) and time.monotonic() < deadline:
            time.sleep(0.05)
        left = [k for k in kids if alive(k)]
        for k in left:
            os.kill(k, signal.SIGKILL)
        assert not left, f"{sig.name}: runs {left} outlived the experiment"
        print(f"{sig.name} to the experiment: its {len(kids)} runs ended with it")


if __name__ == "__main__":
    main()
