#!/usr/bin/env python3
"""Example of docs/python.md: leap-frog and implicit Euler on the paper's combination 4, stepped
from Python, and the cloth's vibration in the window after the hold, with drapelab.analysis's
spectral vibration metric (docs/analysis.md, "Vibration").

Usage: vibration_after_hold.py [OUT.png]   (default vibration_after_hold.png)
Prints one line per method: its step, the hold's time and the vibration RMS [mm].
"""
import sys
from pathlib import Path

import matplotlib
import numpy as np

import drapelab
from drapelab.analysis import split_motion, vibration_cutoff, vibration_rms

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402 (after the backend)

SCENE = Path(__file__).resolve().parents[2] / "experiments/scenes/combination4_hold_release_attach.json"
WINDOW = 0.5  # s after the hold (about 0.4 s), the findings' window; r releases at 1.0 s
METHODS = {"leap-frog, 0.2 ms": {"name": "leapfrog", "dt": 2e-4},
           "implicit Euler, 1/30 s": {"name": "implicit-euler", "dt": 1 / 30}}


def after_hold(integrator):
    """Times from the hold [s], positions (T, N, 3) in the window after it, and the cutoff [Hz]."""
    scene = drapelab.load_scene(SCENE, overrides={"integrator": integrator})
    sim = drapelab.Simulation(scene)
    while not sim.events:  # the hold is the scene's first event
        sim.step()
    hold = sim.time
    times, frames = [0.0], [sim.positions.copy()]  # copies: sim.positions is a view
    while sim.time < hold + WINDOW:
        sim.advance(sim.time + 1e-3)  # every millisecond, or every step when steps are longer
        times.append(sim.time - hold)
        frames.append(sim.positions.copy())
    cutoff = vibration_cutoff({"scene": scene.to_dict(), "events": sim.events})
    return hold, np.array(times), np.array(frames), cutoff


def main():
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path("vibration_after_hold.png")
    fig, ax = plt.subplots(figsize=(6, 3.5))
    for label, integrator in METHODS.items():
        hold, t, x, cutoff = after_hold(integrator)
        grid, _, fast = split_motion(t, x, cutoff)
        ax.plot(grid, 1e3 * np.sqrt((fast**2).sum(axis=-1).mean(axis=-1)), label=label)
        print(f"{label}: hold at {hold:.4f} s, vibration above {cutoff:.2f} Hz: "
              f"{1e3 * vibration_rms(t, x, cutoff):.3f} mm RMS")
    ax.set_xlabel("time after the hold [s]")
    ax.set_ylabel("motion above the cutoff, RMS [mm]")
    ax.set_title("Combination 4: vibration after the hold")
    ax.legend()
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
