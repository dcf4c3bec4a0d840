"""drapelab's DIRK steps against an independent implementation on one stiff spring pendulum.

The model problem of docs/findings/energy_gaining_tables.md ("One spring is enough"):
experiments/scenes/swinging_chain.json with two particles, the first pinned, released horizontal at rest length
(h omega about 30 at 1/30 s, the cloth's spring, mass and damping). Here every stage of a
diagonally implicit Runge-Kutta table is solved by SciPy's MINPACK hybrid method (fsolve) from
the stage's known part, in a dozen lines that share nothing with drapelab but the equations of
docs/model.md; drapelab solves them with ARKODE and its line-search Newton on the incremental
potential, the table given inline (`integrator.table`,
docs/integrators/arkode.md "User tables"). The
energy after every 1/30 s step must agree to 1e-6 of the energy the swing releases, for a table
that settles (KVAERNO_4_2_3), one that gains energy (SDIRK_5_3_4) and one that diverges
(ESDIRK437L2SA). Both follow the stage root from the predictor, and that root is asserted to be
a minimum of the stage's incremental potential (its Jacobian dR/dv, symmetric here, positive
definite): the energy those tables gain is the DIRK map's on its minimising root, the root a
minimiser follows, not a stage solver's accident.

Usage: dirk_reference_pendulum.py DRAPELAB_BINARY [--roots N]
With --roots N every stage is also solved from N random starts (velocities offset by 10 m/s
times a standard normal), and the other roots found are printed with their kind: stages do have
other roots (saddles about 7-9 m/s away, which starts offset by 1 m/s miss); whether any of
them is a minimum too is what the count says.
"""
import csv
import json
import subprocess
import sys
import tempfile
import warnings
from pathlib import Path

import numpy as np
from scipy.optimize import fsolve

ROOT = Path(__file__).resolve().parents[2]
SCENE = ROOT / "experiments" / "scenes" / "swinging_chain.json"
TABLES = json.loads((Path(__file__).parent / "data" / "pendulum_tables.json").read_text())
H = 1.0 / 30.0
STEPS = 12  # 0.4 s: ESDIRK437L2SA diverges in its third step, the others have swung through
RTOL, ATOL = 1e-10, 1e-13  # drapelab's stage tolerance, far below the comparison's 1e-6

scene = json.loads(SCENE.read_text())
cloth = scene["cloth"]
M, K, L = cloth["particle_mass"], cloth["k_structural"], cloth["spacing"]
C_SPRING, C_AIR, G = cloth["damping_spring"], cloth["damping_air"], 9.81


def rhs(y):
    """docs/model.md's right-hand side for the free particle; the pinned one sits at the origin."""
    x, v = y[:3], y[3:]
    r = np.linalg.norm(x)
    u = x / r
    force = -K * (r - L) * u - C_SPRING * (v @ u) * u - C_AIR * v + M * np.array([0.0, -G, 0.0])
    return np.concatenate([v, force / M])


def energy(y):
    x, v = y[:3], y[3:]
    return 0.5 * M * v @ v + 0.5 * K * (np.linalg.norm(x) - L) ** 2 + M * G * x[1]


def lowest_curvature(residual, v, eps=1e-7):
    """The smallest eigenvalue of the symmetric part of dR/dv (central differences): positive at
    a minimum of the stage's incremental potential, whose Hessian is M dR/dv."""
    jacobian = np.column_stack([(residual(v + eps * e) - residual(v - eps * e)) / (2 * eps)
                                for e in np.eye(3)])
    return np.linalg.eigvalsh(0.5 * (jacobian + jacobian.T)).min()


def dirk_step(table, y, starts, rng, roots):
    """One step; `starts` extra random starts per stage. Returns the state; `roots` counts the
    other roots found by kind and keeps the followed roots' lowest curvature."""
    a, b = table["A"], table["b"]
    slopes = []
    for i in range(len(b)):
        known = y + H * sum(a[i][j] * slopes[j] for j in range(i))
        gh = H * a[i][i]
        if gh == 0.0:
            slopes.append(rhs(known))
            continue
        # x = known_x + gh V eliminates the positions: V - known_v - gh a(x, V) = 0.
        state = lambda v: np.concatenate([known[:3] + gh * v, v])  # noqa: E731
        residual = lambda v: v - known[3:] - gh * rhs(state(v))[3:]  # noqa: E731
        v = fsolve(residual, known[3:], xtol=1e-14)
        if np.linalg.norm(residual(v)) > 1e-9:
            raise RuntimeError(f"fsolve found no stage root at stage {i + 1}")
        roots["followed"] = min(roots["followed"], lowest_curvature(residual, v))
        found = []
        for _ in range(starts):
            other = fsolve(residual, known[3:] + 10.0 * rng.standard_normal(3), xtol=1e-14)
            if (np.linalg.norm(residual(other)) <= 1e-9 and np.linalg.norm(other - v) > 1e-6
                    and all(np.linalg.norm(other - w) > 1e-6 for w in found)):
                found.append(other)
                roots["minima" if lowest_curvature(residual, other) > 0 else "saddles"] += 1
        slopes.append(rhs(state(v)))
    return y + H * sum(bj * s for bj, s in zip(b, slopes))


def reference_energies(table, starts):
    """Energies after each step (relative to the start), until the velocity exceeds 1000 m/s,
    and the roots found (dirk_step)."""
    y = np.array([L, 0.0, 0.0, 0.0, 0.0, 0.0])
    e0, out, rng = energy(y), [], np.random.default_rng(1)
    roots = {"followed": np.inf, "minima": 0, "saddles": 0}
    for _ in range(STEPS):
        y = dirk_step(table, y, starts, rng, roots)
        if np.linalg.norm(y[3:]) > 1000.0:
            break
        out.append(energy(y) - e0)
    return out, roots


def drapelab_energies(binary, table, folder):
    """drapelab's energies after each step (relative to the start) and its exit code."""
    result = subprocess.run(
        [binary, "run", str(SCENE), "--out", str(folder), "--set", "cloth.cols=2",
         "--set", f"duration={STEPS * H!r}", "--set", f"integrator.dt={H!r}",
         "--set", f"integrator.rtol={RTOL}", "--set", f"integrator.atol={ATOL}",
         "--set", "integrator.table=" + json.dumps(table)],
        capture_output=True, text=True)
    with open(folder / "energy.csv") as f:
        totals = [float(row["total"]) for row in csv.DictReader(f)]
    return [e - totals[0] for e in totals[1:]], result.returncode


def main():
    binary = sys.argv[1]
    starts = int(sys.argv[3]) if len(sys.argv) > 3 and sys.argv[2] == "--roots" else 0
    # fsolve warns when xtol is below what it can reach: the residual test below decides.
    warnings.filterwarnings("ignore", category=RuntimeWarning, module="scipy")
    released = M * G * L  # the energy the swing releases, the comparison's scale
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        for name, table in TABLES.items():
            reference, roots = reference_energies(table, starts)
            ours, code = drapelab_energies(binary, table, Path(tmp) / name)
            diverged = len(reference) < STEPS
            # drapelab stops on its runaway bound (exit 3), below the reference's 1000 m/s.
            if diverged != (code == 3) or (not diverged and code != 0):
                failures.append(f"{name}: reference {'diverged' if diverged else 'ran'}, "
                                f"drapelab exit {code}")
            n = min(len(reference), len(ours))
            if n == 0 or (not diverged and n < STEPS):
                failures.append(f"{name}: {len(ours)} drapelab steps, {len(reference)} reference")
                continue
            gap = max(abs(p - q) for p, q in zip(reference[:n], ours[:n])) / released
            gained = max(reference[:n]) / released
            print(f"{name}: {n} steps, largest energy difference {gap:.1e} of the released "
                  f"{released:.3e} J; largest energy above the start {gained:+.3f} of it; "
                  f"followed roots' lowest curvature {roots['followed']:.3g}"
                  + (f"; other stage roots found: {roots['minima']} minima, "
                     f"{roots['saddles']} saddles" if starts else ""))
            if gap > 1e-6:
                failures.append(f"{name}: energies differ by {gap:.1e} of the released energy")
            if not roots["followed"] > 0:
                failures.append(f"{name}: a followed stage root is not a minimum "
                                f"(curvature {roots['followed']:.3g})")
        if failures:
            print("\n".join(failures))
            sys.exit(1)


if __name__ == "__main__":
    main()
