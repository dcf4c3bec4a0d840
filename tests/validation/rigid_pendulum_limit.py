"""The stiff spring pendulum's energy gain at 1/30 s is its rigid limit's: a test and a measurement.

docs/findings/energy_gaining_tables.md ("One spring is enough", "And a spring that turns fast"):
on one damped spring pendulum (experiments/scenes/swinging_chain.json with two particles, h omega about 30 at 1/30 s)
five DIRK tables gain energy when the spring turns by about a radian a step, and none when it
turns by 0.1 rad. Here every arkode-dirk table (its coefficients from `drapelab integrators
--table`) also steps the pendulum's stiff limit, a rigid rod of the same length: the index-3
system q' = v, v' = g - lambda q - c_air v / m, |q| = L (Hairer and Wanner, Solving ODEs II,
sec. VII.1; Runge-Kutta methods on it: Hairer, Lubich and Roche 1989, LNM 1409; Lubich 1993,
"Integration of stiff mechanical systems by Runge-Kutta methods", ZAMP 44, analyses when a method
on a stiff spring behaves as on this constrained system). Whether a table's split here matches
the spring's is measured, not assumed.
Every implicit stage then has a closed form: with the stage's known part (q_k, v_k), gamma = h
a_ii and P = q_k + gamma (v_k + gamma g) / (1 + gamma c), the stage position is Q = L P / |P|
(the root on P's side; the other, -L P / |P|, would hold the rod compressed through the pivot),
lambda = (|P| / L - 1) (1 + gamma c) / gamma^2 and V = (Q - q_k) / gamma. An explicit first stage
takes the last stage's lambda of the step before (0 at the unstretched start, as the spring's).
No nonlinear solver is involved.

The test: at L = 0.02 m (the cloth's spacing) and 2 m, the tables whose rigid pendulum ends above
the energy it started with are exactly those whose drapelab spring pendulum ends above it or
diverges (exit 3); at 2 m there are none in either. Prints both energies for every table.

Usage: rigid_pendulum_limit.py DRAPELAB_BINARY [--lengths L ...]
With --lengths the comparison runs at those lengths instead and only prints the tables that gain
(a measurement,
docs/findings/energy_gaining_tables.md: at 0.002 and 0.2 m the two models differ).
"""
import csv
import json
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
SCENE = ROOT / "experiments" / "scenes" / "swinging_chain.json"
cloth = json.loads(SCENE.read_text())["cloth"]
C = cloth["damping_air"] / cloth["particle_mass"]  # air damping per unit mass [1/s]
G = np.array([0.0, -9.81])
H, DURATION = 1.0 / 30.0, 6.0


def rigid_energy_change(table, length):
    """Energy per unit mass at the end minus at the start (inf if it ran away)."""
    a, b = np.array(table["A"]), np.array(table["b"])
    q, v, lam_last = np.array([length, 0.0]), np.zeros(2), 0.0
    energy = lambda q, v: 0.5 * v @ v - G @ q  # noqa: E731
    e0 = energy(q, v)
    for _ in range(round(DURATION / H)):
        vs, fs, lams = [], [], []
        for i in range(len(b)):
            qk = q + H * sum(a[i, j] * vs[j] for j in range(i))
            vk = v + H * sum(a[i, j] * fs[j] for j in range(i))
            gamma = H * a[i, i]
            if gamma == 0.0:  # an ESDIRK's explicit first stage (no other stage is explicit)
                if i > 0:
                    raise ValueError("an explicit stage after the first has no rigid-rod meaning")
                stage_q, stage_v, lam = qk, vk, lam_last
            else:
                p = qk + gamma * (vk + gamma * G) / (1.0 + gamma * C)
                stage_q = length * p / np.linalg.norm(p)
                lam = (np.linalg.norm(p) / length - 1.0) * (1.0 + gamma * C) / gamma**2
                stage_v = (stage_q - qk) / gamma
            vs.append(stage_v)
            fs.append(G - lam * stage_q - C * stage_v)
            lams.append(lam)
        q, v, lam_last = q + H * (b @ np.array(vs)), v + H * (b @ np.array(fs)), lams[-1]
        if not np.isfinite(energy(q, v)) or np.linalg.norm(v) > 1e3:
            return float("inf")
    return energy(q, v) - e0


def spring_energy_change(binary, table, length, folder):
    """drapelab's spring pendulum: energy at the end minus at the start, per unit mass (inf if
    the run diverged)."""
    result = subprocess.run(
        [binary, "run", str(SCENE), "--out", str(folder), "-q", "--set", "cloth.cols=2",
         "--set", f"cloth.spacing={length!r}", "--set", f"duration={DURATION!r}",
         "--set", "integrator.table=" + table],
        capture_output=True, text=True)
    if result.returncode == 3:
        return float("inf")
    if result.returncode != 0:
        raise RuntimeError(f"{table}: drapelab exit {result.returncode}: {result.stderr}")
    with open(folder / "energy.csv") as f:
        totals = [float(row["total"]) for row in csv.DictReader(f)]
    return (totals[-1] - totals[0]) / cloth["particle_mass"]


def main():
    binary = sys.argv[1]
    measure = len(sys.argv) > 2 and sys.argv[2] == "--lengths"
    lengths = [float(a) for a in sys.argv[3:]] if measure else [0.02, 2.0]
    listing = subprocess.run([binary, "integrators"], capture_output=True, text=True, check=True)
    names = [line.split()[1] for line in listing.stdout.splitlines()
             if line.startswith("arkode-dirk ") and line.split()[1].startswith("ARKODE_")]
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        for length in lengths:
            released = -G[1] * length  # per unit mass, from horizontal to the bottom
            gain_rigid, gain_spring = set(), set()
            print(f"L = {length} m: energy change over {DURATION} s, of the swing's {released} J/kg")
            for name in names:
                tableau = json.loads(subprocess.run(
                    [binary, "integrators", "--table", name],
                    capture_output=True, text=True, check=True).stdout)
                rigid = rigid_energy_change(tableau, length)
                spring = spring_energy_change(binary, name, length, Path(tmp) / f"{name}-{length}")
                print(f"  {name:32s} rigid {rigid / released:+10.4g}   spring {spring / released:+10.4g}")
                if rigid > 0.0:
                    gain_rigid.add(name)
                if spring > 0.0:
                    gain_spring.add(name)
            print(f"  gain: rigid {len(gain_rigid)}, spring {len(gain_spring)}; only rigid "
                  f"{sorted(gain_rigid - gain_spring)}, only spring {sorted(gain_spring - gain_rigid)}")
            if measure:
                continue
            if gain_rigid != gain_spring:
                failures.append(f"L = {length}: only rigid {sorted(gain_rigid - gain_spring)}, "
                                f"only spring {sorted(gain_spring - gain_rigid)}")
            if length == 0.02 and not gain_rigid:
                failures.append("L = 0.02: no table gains: the comparison would be vacuous")
            if length == 2.0 and gain_rigid:
                failures.append(f"L = 2: tables gain on the slowly turning rod: {sorted(gain_rigid)}")
    if failures:
        print("\n".join(failures))
        sys.exit(1)


if __name__ == "__main__":
    main()
