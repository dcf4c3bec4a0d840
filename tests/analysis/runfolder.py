"""Writes small synthetic run folders (docs/outputs.md) for the analysis tests, and makes
analysis/drapeanalysis importable however the tests are started."""
import json
import math
import os
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

import numpy as np

ANALYSIS_DIR = Path(__file__).resolve().parents[2] / "analysis"
if str(ANALYSIS_DIR) not in sys.path:
    sys.path.insert(0, str(ANALYSIS_DIR))

# A cloth whose model frequencies (spectral.model_frequencies) are known: combination 1's,
# swing 0.809 Hz, stretch 14.7 Hz, cutoff 3.449 Hz.
CLOTH_SCENE = {"cloth": {"rows": 20, "cols": 20, "spacing": 0.02, "particle_mass": 6e-5,
                         "k_structural": 50, "k_shear": 50}, "pins": [[0, 10]]}

TRACE_HEADER = "t,index,x,y,z,vx,vy,vz,fixed,contact,event"
STATE_HEADER = "index,row,col,x,y,z,vx,vy,vz,fixed"


def unit_directions(n):
    """n unit vectors in different directions, (n, 3), n <= 5."""
    d = np.array([[1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 1], [1, -2, 0.5]], float)[:n]
    return d / np.linalg.norm(d, axis=1, keepdims=True)


def trace_dict(t, x, v=None, fixed=None, contact=None):
    """What runfiles.trace_frames returns, built in memory."""
    k, n = x.shape[:2]
    return {
        "t": np.asarray(t, float), "x": x, "v": np.zeros_like(x) if v is None else v,
        "fixed": np.zeros((k, n), bool) if fixed is None else fixed,
        "contact": -np.ones((k, n), int) if contact is None else contact,
        "event": np.zeros(k, bool),
    }


def write_csv(path, header, rows):
    """A CSV file with `header` (a comma-separated string) and numeric rows, 17 digits."""
    with open(path, "w") as f:
        f.write(header + "\n")
        for row in rows:
            f.write(",".join(v if isinstance(v, str) else f"{v:.17g}" for v in row) + "\n")


def write_summary(run, events=(), scene=None, **extra):
    """summary.json with the given events and scene."""
    doc = {"status": "ok", "events": list(events), "scene": scene or {}}
    doc.update(extra)
    (run / "summary.json").write_text(json.dumps(doc))


def write_energy(run, t, total):
    """energy.csv with the total energy `total` (the parts are not read by the metrics)."""
    write_csv(run / "energy.csv", "t,kinetic,spring,gravity,collision,total",
              [(ti, 0.0, 0.0, 0.0, 0.0, ei) for ti, ei in zip(t, total)])


def write_state(run, x, cols=1, v=None, fixed=None):
    """state.csv of positions x (N, 3), particles numbered row-major in a grid of `cols` columns."""
    x = np.asarray(x, dtype=float)
    v = np.zeros_like(x) if v is None else v
    fixed = np.zeros(len(x), dtype=int) if fixed is None else fixed
    write_csv(run / "state.csv", STATE_HEADER,
              [(i, i // cols, i % cols, *x[i], *v[i], int(fixed[i])) for i in range(len(x))])


def write_trace(run, t, x, v=None, fixed=None, contact=None, event=None):
    """trace.csv of K frames of N particles: t (K,), x and v (K, N, 3), fixed and contact (K, N),
    event (K,)."""
    t = np.asarray(t, dtype=float)
    k, n = x.shape[:2]
    v = np.zeros_like(x) if v is None else v
    fixed = np.zeros((k, n), dtype=int) if fixed is None else fixed
    contact = -np.ones((k, n), dtype=int) if contact is None else contact
    event = np.zeros(k, dtype=int) if event is None else event
    lines = [TRACE_HEADER]
    for a in range(k):
        for i in range(n):
            values = (t[a], x[a, i, 0], x[a, i, 1], x[a, i, 2], v[a, i, 0], v[a, i, 1], v[a, i, 2])
            lines.append("%.17g,%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%d,%d,%d" % (
                values[0], i, *values[1:], int(fixed[a, i]), int(contact[a, i]), int(event[a])))
    (run / "trace.csv").write_text("\n".join(lines) + "\n")


def write_event_trace(run, t, x):
    """event_trace/ (docs/outputs.md) with frames at times t of positions x (K, N, 3), at rest,
    free and out of contact."""
    folder = run / "event_trace"
    folder.mkdir()
    frames, particles = x.shape[0], x.shape[1]
    np.save(folder / "t.npy", np.asarray(t, np.float64))
    np.save(folder / "x.npy", x.astype(np.float32))
    np.save(folder / "v.npy", np.zeros((frames, particles, 3), np.float32))
    np.save(folder / "fixed.npy", np.zeros((frames, particles), np.uint8))
    np.save(folder / "contact.npy", -np.ones((frames, particles), np.int32))


def write_hands(run, rows):
    """hands.csv from (t, hand, available, x, y, z) rows; candidate, distance, held filled in."""
    write_csv(run / "hands.csv", "t,hand,available,x,y,z,candidate,distance,held",
              [(t, hand, int(avail), x, y, z, -1, 0.0, -1) for t, hand, avail, x, y, z in rows])


def write_experiment(directory, scenes=("scenes/a.json", "scenes/b.json"), steps=(0.001, 0.002)):
    """A small experiment folder: a leapfrog run per scene and step on a 3 x 4 cloth swinging
    and vibrating at 40 Hz (trace every 5 ms over 1 s), a hold at 0.3 s and a release at 0.6 s,
    an object of 3 rings of 8 object particles; results.json lists the runs."""
    rows, cols, frames = 3, 4, 201
    t = np.arange(frames) * 0.005
    r, c = np.divmod(np.arange(rows * cols), cols)
    base = np.stack([0.05 * c, 1.2 - 0.05 * r, np.full(r.shape, 0.2)], axis=1)
    angle = np.tile(np.arange(8) * np.pi / 4, 3)
    ring = np.repeat(np.arange(3), 8)
    dummy = [(i, ring[i], i % 8, 0.05 * np.cos(angle[i]), 1.0 + 0.1 * ring[i], 0.05 * np.sin(angle[i]),
              0.0, 0.0, 1.0) for i in range(24)]
    events = [{"t": 0.3, "type": "hold", "hand": "right"}, {"t": 0.6, "type": "release", "hand": "right"}]
    runs = []
    for scene in scenes:
        for k, dt in enumerate(steps):
            name = f"{scene.rsplit('/', 1)[-1][:-5]}-{dt}"
            run = directory / "runs" / name
            run.mkdir(parents=True)
            write_summary(run, events, CLOTH_SCENE | {"cloth": {**CLOTH_SCENE["cloth"], "rows": rows, "cols": cols}},
                          sim_time=float(t[-1]))
            x = (base[None] + 0.02 * np.sin(2 * np.pi * 0.8 * t)[:, None, None] * [1, 0, 0]
                 + (1 + k) * 1e-3 * np.sin(2 * np.pi * 40 * t)[:, None, None] * [0, 0, 1])
            fixed = np.zeros((frames, rows * cols), int)
            fixed[:, 0] = 1
            write_trace(run, t, x, fixed=fixed)
            write_state(run, x[-1], cols=cols, fixed=fixed[-1])
            write_energy(run, t, -1.0 + 1e-3 * np.sin(2 * np.pi * t) * (1 + k))
            write_csv(run / "dummy.csv", "index,section,point,x,y,z,nx,ny,nz", dummy)
            runs.append({"id": name, "run_dir": f"runs/{name}", "index": len(runs), "scene": scene,
                         "integrator": "leapfrog", "integrator.name": "leapfrog", "integrator.dt": dt,
                         "status": "ok", "steps": int(1 / dt), "rhs_evals": int(1 / dt),
                         "wall_seconds": 0.1 * (k + 1), "events": len(events)})
            (run / "result.json").write_text(json.dumps(runs[-1]))
    columns = list(runs[0])
    (directory / "results.json").write_text(json.dumps({
        "name": "synthetic", "question": "q?", "metrics": [], "parameters": ["integrator.name", "integrator.dt"],
        "plan_size": len(runs), "columns": columns, "runs": runs}))
    return runs


def run_report(directory, *args, timeout=120, env=None, **kwargs):
    """report.py DIR ARGS with this tree's drapeanalysis (and `env` added to the environment), as
    a finished subprocess (its output as text); a timeout fails the test instead of blocking it
    (a report reading a named pipe)."""
    env = {**os.environ, "PYTHONPATH": str(ANALYSIS_DIR), "PYTHONDONTWRITEBYTECODE": "1", **(env or {})}
    return subprocess.run([sys.executable, str(ANALYSIS_DIR / "report.py"), str(directory), *map(str, args)],
                          capture_output=True, text=True, env=env, timeout=timeout, **kwargs)


class RunFolderTest(unittest.TestCase):
    """A fresh experiment folder per test, with run folders under runs/."""

    def setUp(self):
        self._tmp = tempfile.TemporaryDirectory()
        self.directory = Path(self._tmp.name)

    def tearDown(self):
        self._tmp.cleanup()

    def make_run(self, name="a"):
        run = self.directory / "runs" / name
        run.mkdir(parents=True)
        return run

    def row(self, name="a", **extra):
        return {"id": name, "run_dir": f"runs/{name}", **extra}

    def assertClose(self, actual, expected, rel=1e-9, abs_tol=0.0, msg=None):
        self.assertTrue(math.isclose(actual, expected, rel_tol=rel, abs_tol=abs_tol),
                        msg or f"{actual!r} != {expected!r} (rel {rel}, abs {abs_tol})")
