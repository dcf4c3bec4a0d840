#!/usr/bin/env python3
"""Example: load an experiment folder with drapeanalysis and redraw one figure of its report,
the energy of every run of one scene, in the report's style.

Usage: redraw_figure.py DIR [--scene NAME] [--out STEM]
DIR is an experiment folder (`drapelab experiment ... --out DIR`); NAME a scene's file stem
(default: the first scene); writes STEM.png, .svg and .pdf (default DIR/report/redrawn_energy).
Needs only `import drapeanalysis` (install_dependencies.sh puts analysis/ on python3's path).
"""
import argparse
from pathlib import Path

import matplotlib.pyplot as plt

import drapeanalysis
from drapeanalysis import style


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("directory", type=Path)
    parser.add_argument("--scene")
    parser.add_argument("--out", type=Path)
    args = parser.parse_args()
    runs = drapeanalysis.results_table(args.directory)  # one row per run, a pandas DataFrame
    runs["scene_name"] = runs["scene"].str.rsplit("/", n=1).str[-1].str.removesuffix(".json")
    scene = args.scene or runs["scene_name"].iloc[0]
    runs = runs[runs["scene_name"] == scene]
    if runs.empty:
        raise SystemExit(f"{args.directory}: no run of scene {scene}")
    fig, ax = plt.subplots(figsize=(6.5, 3.5))
    for k, (_, row) in enumerate(runs.iterrows()):
        energy_file = args.directory / row["run_dir"] / "energy.csv"
        if not energy_file.exists():
            continue
        energy = drapeanalysis.read_energy(energy_file)  # a DataFrame: t, kinetic, ..., total
        name = f"{row.get('integrator', '?')} dt={row.get('integrator.dt', row.get('dt'))}"
        ax.plot(energy["t"], 1e3 * (energy["total"] - energy["total"].iloc[0]), label=name,
                color=style.integrator_color(row.to_dict(), "k"), ls=style.LINE_STYLES[k % 6])
    summary = drapeanalysis.read_summary(args.directory / runs["run_dir"].iloc[0])
    style.mark_events(ax, [(float(e["t"]), e["type"]) for e in summary.get("events", [])
                           if e.get("type") != "ignored"])
    ax.set_title(scene)
    ax.set_xlabel("t [s]")
    ax.set_ylabel("E(t) - E(0) [mJ]")
    style.legend_beside(ax)
    out = args.out or args.directory / "report" / "redrawn_energy"
    out.parent.mkdir(parents=True, exist_ok=True)
    style.save(fig, out.parent, out.name)
    print(out.with_suffix(".png"))


if __name__ == "__main__":
    main()
