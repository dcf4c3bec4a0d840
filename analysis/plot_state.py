#!/usr/bin/env python3
"""Front and side views of a run's cloth (state.csv) on its dress form, like the paper's figures.

Grey: object particles (dummy.csv); blue: free cloth particles; red: fixed ones (pinned, held,
attached); green stars: tracked hands at the final time (hands.csv).

Usage: plot_state.py RUN_DIR [--out FILE.png] [--dummy dummy.csv]
Reads only the files a run writes (docs/outputs.md).
"""
import argparse
import csv
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit(f"{path}: no rows")
    return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("run_dir", type=Path)
    parser.add_argument("--out", type=Path)
    args = parser.parse_args()
    state = read_csv(args.run_dir / "state.csv")
    dummy_file = args.run_dir / "dummy.csv"
    dummy = read_csv(dummy_file) if dummy_file.exists() else []
    hands_file = args.run_dir / "hands.csv"
    hands = read_csv(hands_file) if hands_file.exists() else []
    # The hands at the last output time, where the state was written.
    hands = [h for h in hands if h["t"] == hands[-1]["t"] and h["available"] == "1"] if hands else []

    fig, axes = plt.subplots(1, 2, figsize=(9, 6), sharey=True)
    for ax, (h, title) in zip(axes, (("x", "front (+z towards viewer)"), ("z", "side (+z to the right)"))):
        if dummy:
            ax.scatter([float(p[h]) for p in dummy], [float(p["y"]) for p in dummy], s=1, c="0.75")
        fixed = [p for p in state if p["fixed"] == "1"]
        free = [p for p in state if p["fixed"] != "1"]
        ax.scatter([float(p[h]) for p in free], [float(p["y"]) for p in free], s=2, c="tab:blue")
        ax.scatter([float(p[h]) for p in fixed], [float(p["y"]) for p in fixed], s=12, c="tab:red")
        for hand in hands:
            ax.scatter([float(hand[h])], [float(hand["y"])], s=80, marker="*", c="tab:green")
        ax.set_title(title)
        ax.set_xlabel(f"{h} [m]")
        ax.set_aspect("equal")
    axes[0].set_ylabel("y [m]")
    out = args.out or args.run_dir / "state.png"
    fig.savefig(out, dpi=110, bbox_inches="tight")
    print(out)


if __name__ == "__main__":
    main()
