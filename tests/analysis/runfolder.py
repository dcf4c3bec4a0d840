"""Writes small synthetic run folders (docs/outputs.md) for the analysis tests, and makes
analysis/drapeanalysis importable however the tests are started."""
import json
import sys
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


def write_hands(run, rows):
    """hands.csv from (t, hand, available, x, y, z) rows; candidate, distance, held filled in."""
    write_csv(run / "hands.csv", "t,hand,available,x,y,z,candidate,distance,held",
              [(t, hand, int(avail), x, y, z, -1, 0.0, -1) for t, hand, avail, x, y, z in rows])
