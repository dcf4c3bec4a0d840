"""Runs shipped scenes with every integrator on 1, 2 and 3 threads and checks that state.csv and
energy.csv are the same bytes (docs/performance/threads.md, "The same bits on any number of
threads"), that summary.json records the threads, and that a bad --threads or DRAPELAB_THREADS
is refused with exit 2 naming the flag.

The cloths are 100 x 100 (the scenes' 20 x 20 is below the 2048 particles from which the loops
run on threads, core/parallel/parallel_for.hpp; vbd's colours hold a quarter of the particles
each), for a few steps: the implicit integrators at 1/30 s,
the explicit ones at the scene's dt.

Usage: threads_bit_identity.py DRAPELAB SOURCE_DIR WORK_DIR"""
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

THREADS = (1, 2, 3)
SIZE = ["cloth.rows=100", "cloth.cols=100", "output.energy_interval=0.002"]


def steps(declaration):
    """The integrator and a few of its steps: the scene's dt for an explicit one, 1/30 s else."""
    chosen = [f"integrator.name={declaration['name']}"]
    if declaration["family"] == "explicit":
        return chosen + ["duration=0.01"]
    return chosen + ["integrator.dt=0.03333333333333333", "duration=0.1"]


def run(drapelab, scene, out, threads, overrides):
    cmd = [drapelab, "run", str(scene), "--out", str(out), "--quiet", "--threads", str(threads),
           "--set", *overrides]
    done = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
    if done.returncode not in (0, 3):
        sys.exit(f"{' '.join(cmd)}: exit {done.returncode}\n{done.stderr}")
    summary = json.loads((out / "summary.json").read_text())
    if summary.get("threads") != threads:
        sys.exit(f"{out}: summary.json threads {summary.get('threads')}, expected {threads}")
    return summary["status"]


def compare(drapelab, scene, work, label, overrides):
    outs = [work / f"{label}-t{n}" for n in THREADS]
    statuses = [run(drapelab, scene, out, n, overrides) for out, n in zip(outs, THREADS)]
    if len(set(statuses)) != 1:
        return f"{label}: status {statuses} on {THREADS} threads"
    names = ["energy.csv"] + (["state.csv"] if statuses[0] == "ok" else [])
    for name in names:
        first = (outs[0] / name).read_bytes()
        for out, n in zip(outs[1:], THREADS[1:]):
            if (out / name).read_bytes() != first:
                return f"{label}: {name} on {n} threads differs from 1 thread"
    print(f"{label}: {statuses[0]}, {' and '.join(names)} identical on {THREADS} threads")
    return None


def check_refused(drapelab, scene, work):
    bad = ["0", "-2", "1.5", "two", "100000"]
    for value in bad:
        for how in ("flag", "env"):
            cmd = [drapelab, "run", str(scene), "--out", str(work / "refused"), "--quiet"]
            env = dict(os.environ)
            if how == "flag":
                cmd += ["--threads", value]
            else:
                env["DRAPELAB_THREADS"] = value
            done = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=60)
            if done.returncode != 2 or "--threads" not in done.stderr:
                return f"--threads {value} ({how}): exit {done.returncode}, stderr {done.stderr!r}"
    return None


def main():
    drapelab, source, work = sys.argv[1], Path(sys.argv[2]), Path(sys.argv[3])
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    listed = json.loads(subprocess.run([drapelab, "integrators", "--json"], capture_output=True,
                                       text=True, check=True).stdout)
    declarations = listed["integrators"] if isinstance(listed, dict) else listed
    scenes = source / "experiments" / "scenes"
    failures = [check_refused(drapelab, scenes / "fig2_hold.json", work)]
    for d in declarations:
        failures.append(compare(drapelab, scenes / "fig2_hold.json", work, d["name"],
                                SIZE + steps(d)))
    # The smooth contact model's own force loop.
    for d in (d for d in declarations if d["name"] in ("leapfrog", "implicit-euler")):
        failures.append(compare(drapelab, scenes / "drape_dress_form.json", work,
                                d["name"] + "-smooth", SIZE + steps(d) + ["collision.model=smooth"]))
    failures = [f for f in failures if f]
    for f in failures:
        print("FAILED:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
