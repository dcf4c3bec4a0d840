"""The report's figures; each function saves PNG and SVG and returns the file stem, or None
when the table has nothing to plot."""
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from . import runfiles  # noqa: E402

MAX_SNAPSHOT_RUNS = 4


def save(fig, out_dir, stem):
    """Writes the figure as PNG and SVG and closes it."""
    fig.savefig(out_dir / f"{stem}.png", dpi=110, bbox_inches="tight")
    fig.savefig(out_dir / f"{stem}.svg", bbox_inches="tight")
    plt.close(fig)
    return stem


def label(row, parameters, exclude=()):
    """A series name: the run's parameter values, keys shortened to their last part."""
    parts = [f"{key.split('.')[-1]}={row[key]}" for key in parameters if key not in exclude and key in row]
    return ", ".join(parts) or row["scene"]


def number(value):
    """A float, nan for missing or non-numeric cells."""
    try:
        return float(value)
    except (TypeError, ValueError):
        return math.nan


def series(rows, parameters, x_key, y_key, exclude=()):
    """Points (x, y) grouped by label, sorted by x, finite values only."""
    groups = {}
    for row in rows:
        x, y = number(row.get(x_key)), number(row.get(y_key))
        if math.isfinite(x) and math.isfinite(y) and not row.get("is_reference"):
            groups.setdefault(label(row, parameters, (x_key,) + tuple(exclude)), []).append((x, y))
    return {name: sorted(points) for name, points in groups.items()}


def line_plot(out_dir, stem, rows, parameters, x_key, y_key, xlabel, ylabel, logx=True, logy=True):
    """One line per series of y against x."""
    groups = series(rows, parameters, x_key, y_key)
    if not groups:
        return None
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for name, points in groups.items():
        xs, ys = zip(*points)
        ax.plot(xs, ys, "o-", label=name, markersize=4)
    ax.set_xscale("log" if logx else "linear")
    ax.set_yscale("log" if logy and all(y > 0 for p in groups.values() for _, y in p) else "linear")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    return save(fig, out_dir, stem)


def energy_vs_time(directory, out_dir, rows, parameters):
    """Relative energy error |E(t) - E(0)| / |E(0)| of every run, one panel per integrator."""
    by_integrator = {}
    for row in rows:
        run = runfiles.run_dir(directory, row)
        if (run / "energy.csv").exists() and not row.get("is_reference"):
            by_integrator.setdefault(row.get("integrator", "?"), []).append((row, run))
    if not by_integrator:
        return None
    fig, axes = plt.subplots(len(by_integrator), 1, figsize=(7, 2.6 * len(by_integrator)),
                             squeeze=False, sharex=True)
    for ax, (name, runs) in zip(axes[:, 0], sorted(by_integrator.items())):
        for row, run in runs:
            energy = runfiles.read_table(run / "energy.csv")
            rel = np.abs(energy["total"] - energy["total"][0]) / max(abs(energy["total"][0]), 1e-300)
            ax.plot(energy["t"], np.maximum(rel, 1e-17), lw=0.8,
                    label=label(row, parameters, ("integrator.name",)))
        ax.set_yscale("log")
        ax.set_title(name, fontsize=9)
        ax.set_ylabel("|E - E0| / |E0|")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=6)
    axes[-1, 0].set_xlabel("t [s]")
    return save(fig, out_dir, "energy_vs_time")


def work_precision(out_dir, rows, parameters):
    """Error against the reference run vs right-hand-side evaluations and wall time."""
    groups = {key: series(rows, parameters, key, "error_rms", ("integrator.dt",))
              for key in ("rhs_evals", "wall_seconds")}
    if not any(groups.values()):
        return None
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5), sharey=True)
    for ax, (key, data) in zip(axes, groups.items()):
        for name, points in data.items():
            xs, ys = zip(*points)
            ax.plot(xs, ys, "o-", label=name, markersize=4)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("right-hand-side evaluations" if key == "rhs_evals" else "wall time [s]")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel("RMS position error vs reference [m]")
    axes[1].legend(fontsize=7)
    return save(fig, out_dir, "work_precision")


def stable_dt(out_dir, rows, parameters):
    """Largest stable value found by bisection, one bar per run."""
    found = [(label(row, parameters), number(row.get("stable_value"))) for row in rows]
    found = [(name, value) for name, value in found if math.isfinite(value)]
    if not found:
        return None
    fig, ax = plt.subplots(figsize=(7, 0.4 * len(found) + 1.5))
    names, values = zip(*found)
    ax.barh(range(len(found)), values)
    ax.set_yticks(range(len(found)), names, fontsize=7)
    ax.set_xscale("log")
    ax.set_xlabel(f"largest stable {rows[0].get('bisect_parameter', 'dt')}")
    ax.grid(True, axis="x", which="both", alpha=0.3)
    return save(fig, out_dir, "stable_dt")


def snapshots(directory, out_dir, rows):
    """Front and side views of the cloth on the object at every event and at the end (trace.csv)."""
    stems = []
    for row in rows:
        run = runfiles.run_dir(directory, row)
        if len(stems) >= MAX_SNAPSHOT_RUNS or not (run / "trace.csv").exists():
            continue
        trace = runfiles.read_trace(run / "trace.csv")
        frames = np.unique(np.append(np.nonzero(trace["event"])[0], len(trace["t"]) - 1))
        dummy = runfiles.read_table(run / "dummy.csv") if (run / "dummy.csv").exists() else None
        fig, axes = plt.subplots(2, len(frames), figsize=(2.6 * len(frames), 6.5), squeeze=False)
        for col, k in enumerate(frames):
            for ax, (h, view) in zip(axes[:, col], (("x", "front"), ("z", "side"))):
                if dummy is not None:
                    ax.scatter(dummy[h], dummy["y"], s=0.5, c="0.8")
                x = trace["x"][k]
                fixed = trace["fixed"][k]
                axis = 0 if h == "x" else 2
                ax.scatter(x[~fixed, axis], x[~fixed, 1], s=1.5, c="tab:blue")
                ax.scatter(x[fixed, axis], x[fixed, 1], s=8, c="tab:red")
                ax.set_aspect("equal")
                ax.set_title(f"{view}, t = {trace['t'][k]:.3g} s", fontsize=8)
                ax.tick_params(labelsize=6)
        fig.suptitle(row["id"], fontsize=8)
        stems.append(save(fig, out_dir, f"snapshots_{row['index']}"))
    return stems
