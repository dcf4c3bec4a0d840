"""The report's figures; each function saves PNG and SVG and returns the file stem, or None
when the table has nothing to plot."""
import math
import warnings

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from . import runfiles  # noqa: E402

MAX_SNAPSHOT_RUNS = 4


def save(fig, out_dir, stem):
    """Writes the figure as PNG and SVG and closes it."""
    with warnings.catch_warnings():  # figures with large legends cannot always be tightened
        warnings.simplefilter("ignore")
        fig.tight_layout()  # keeps panel titles clear of the axis labels above them
    fig.savefig(out_dir / f"{stem}.png", dpi=110, bbox_inches="tight")
    fig.savefig(out_dir / f"{stem}.svg", bbox_inches="tight")
    plt.close(fig)
    return stem


# Keys that never name a series: they vary with the x value by construction (a case's duration
# is set from its attach iterations, for example).
NEVER_IN_LABEL = ("duration",)


def scene_name(row):
    """The scene's file stem (scenes/combination1_hold_release.json -> combination1_hold_release)."""
    return str(row.get("scene", "")).rsplit("/", 1)[-1].removesuffix(".json")


def label(row, parameters, exclude=(), with_scene=False):
    """A series name: the run's parameter values, keys shortened to their last part (and the
    scene when asked)."""
    parts = [f"{key.split('.')[-1]}={row[key]}" for key in parameters
             if key not in exclude and key not in NEVER_IN_LABEL and key in row]
    if with_scene:
        parts.insert(0, scene_name(row))
    return ", ".join(parts) or scene_name(row)


def several_scenes(rows):
    """True when the table has runs of more than one scene (series must then name it)."""
    return len({row.get("scene") for row in rows}) > 1


def number(value):
    """A float, nan for missing or non-numeric cells."""
    try:
        return float(value)
    except (TypeError, ValueError):
        return math.nan


def series(rows, parameters, x_key, y_key, exclude=()):
    """Points (x, y) grouped by label, sorted by x, finite values only. x_key may be a function
    of the row."""
    groups = {}
    scenes = several_scenes(rows)
    for row in rows:
        x = number(x_key(row) if callable(x_key) else row.get(x_key))
        y = number(row.get(y_key))
        if math.isfinite(x) and math.isfinite(y) and not row.get("is_reference"):
            key = label(row, parameters, ((x_key,) if isinstance(x_key, str) else ()) + tuple(exclude),
                        with_scene=scenes)
            groups.setdefault(key, []).append((x, y))
    return {name: sorted(points) for name, points in groups.items()}


def line_plot(out_dir, stem, rows, parameters, x_key, y_key, xlabel, ylabel, logx=True, logy=True,
              exclude=()):
    """One line per series of y against x."""
    groups = series(rows, parameters, x_key, y_key, exclude)
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
    scenes = several_scenes(rows)
    fig, axes = plt.subplots(len(by_integrator), 1, figsize=(7, 2.6 * len(by_integrator)),
                             squeeze=False, sharex=True)
    for ax, (name, runs) in zip(axes[:, 0], sorted(by_integrator.items())):
        for row, run in runs:
            energy = runfiles.read_energy(run / "energy.csv")
            total = energy["total"].to_numpy()
            rel = np.abs(total - total[0]) / max(abs(total[0]), 1e-300)
            ax.plot(energy["t"], np.maximum(rel, 1e-17), lw=0.8,
                    label=label(row, parameters, INTEGRATOR_DETAIL, with_scene=scenes))
        ax.set_yscale("log")
        ax.set_ylim(bottom=1e-8)  # round-off at the first rows would squash the scale
        ax.set_title(name, fontsize=9)
        ax.set_ylabel("|E - E0| / |E0|")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=6)
    axes[-1, 0].set_xlabel("t [s]")
    return save(fig, out_dir, "energy_vs_time")


# Integrator keys that only qualify the method (its name and step already tell it apart).
INTEGRATOR_DETAIL = ("integrator.name", "integrator.table", "integrator.adaptive",
                     "integrator.linear_solver")


# One colour per integrator in every figure.
INTEGRATOR_COLORS = {"leapfrog": "tab:blue", "symplectic-euler": "tab:orange",
                     "implicit-euler": "tab:green", "arkode-erk": "tab:red",
                     "arkode-dirk": "tab:purple", "arkode-imex": "tab:brown"}


def integrator_color(row, default=None):
    """The colour of a run's integrator (default for unknown names)."""
    return INTEGRATOR_COLORS.get(row.get("integrator.name") or row.get("integrator"), default)


def method_label(row):
    """Short name of a run's method: integrator and step."""
    return f"{row.get('integrator', '?')} dt={row.get('integrator.dt', row.get('dt'))}"


def event_times(directory, row):
    """(time, type) of the run's manipulations, from summary.json."""
    path = runfiles.run_dir(directory, row) / "summary.json"
    if not path.exists():
        return []
    return [(float(e["t"]), e["type"]) for e in runfiles.read_summary(path.parent).get("events", [])
            if e.get("type") != "ignored"]


def energy_by_scene(directory, out_dir, rows, parameters):
    """Total energy E(t) - E(0) of every method, one panel per scene, events marked: in driven,
    damped scenes energy is not conserved, so the methods are compared with each other (and with
    the reference run, black)."""
    by_scene = {}
    for row in rows:
        run = runfiles.run_dir(directory, row)
        if (run / "energy.csv").exists():
            by_scene.setdefault(scene_name(row), []).append((row, run))
    if len(by_scene) < 1 or not any(row.get("events") for row in rows):
        return None
    fig, axes = plt.subplots(len(by_scene), 1, figsize=(8, 2.9 * len(by_scene)), squeeze=False)
    for ax, (name, runs) in zip(axes[:, 0], by_scene.items()):
        for row, run in runs:
            energy = runfiles.read_energy(run / "energy.csv")
            style = (dict(c="k", lw=1.6, ls="--") if row.get("is_reference") else
                     dict(lw=0.9, c=integrator_color(row),
                          ls="-" if row is min((r for r, _ in runs if integrator_color(r) == integrator_color(row)),
                                               key=lambda r: number(r.get("integrator.dt"))) else "--"))
            text = method_label(row) + (" (reference)" if row.get("is_reference") else "")
            if row.get("status") not in (None, "ok"):
                text += f" [{row.get('status')}]"
            ax.plot(energy["t"], 1e3 * (energy["total"] - energy["total"].iloc[0]), label=text, **style)
        for t, kind in event_times(directory, runs[0][0]):
            ax.axvline(t, c="0.5", lw=0.6, ls=":")
            ax.text(t, 1.0, " " + kind, transform=ax.get_xaxis_transform(), fontsize=7, va="top")
        ax.set_title(name, fontsize=9)
        ax.set_ylabel("E(t) - E(0) [mJ]")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=6, ncol=2)
    axes[-1, 0].set_xlabel("t [s]")
    return save(fig, out_dir, "energy_by_scene")


def work_precision(out_dir, rows, parameters):
    """Error against the reference run vs right-hand-side evaluations and wall time, one row of
    panels per scene, one line per integrator (its steps joined)."""
    by_scene = {}
    for row in rows:
        if not row.get("is_reference") and math.isfinite(number(row.get("error_rms"))):
            by_scene.setdefault(scene_name(row), []).append(row)
    if not by_scene:
        return None
    fig, axes = plt.subplots(len(by_scene), 2, figsize=(11, 3.4 * len(by_scene)), squeeze=False,
                             sharey="row")
    for r, (name, scene_rows) in enumerate(by_scene.items()):
        for c, key in enumerate(("rhs_evals", "wall_seconds")):
            ax = axes[r, c]
            groups, colors = {}, {}
            for row in scene_rows:
                rest = label(row, parameters, ("integrator.dt",) + INTEGRATOR_DETAIL)
                key_name = str(row.get("integrator", "?")) + (f", {rest}" if rest != scene_name(row) else "")
                colors[key_name] = integrator_color(row)
                groups.setdefault(key_name, []).append(
                    (number(row.get(key)), number(row.get("error_rms")), row.get("integrator.dt")))
            for series_name, points in sorted(groups.items()):
                points.sort()
                xs, ys, dts = zip(*points)
                line, = ax.plot(xs, ys, "o-", label=series_name, markersize=4, color=colors[series_name])
                for x, y, dt in points:
                    ax.annotate(f"{dt}", (x, y), fontsize=6, xytext=(3, 3), textcoords="offset points",
                                color=line.get_color())
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_title(name, fontsize=9)
            ax.set_xlabel("right-hand-side evaluations" if key == "rhs_evals" else "wall time [s]")
            ax.grid(True, which="both", alpha=0.3)
        axes[r, 0].set_ylabel("RMS final position error [m]")
    axes[0, 1].legend(fontsize=6)
    return save(fig, out_dir, "work_precision")


def vibration_vs_dt(out_dir, rows, parameters, y_key="vibration_rms_final",
                    ylabel="vibration RMS, last 0.5 s [m]", stem="vibration_vs_dt"):
    """y against the step, one panel per scene and collision model (when swept), one line per
    integrator and the other swept values; the step axis spans all methods."""
    if "integrator.dt" not in parameters:
        return None
    panels, colors = {}, {}
    for row in rows:
        y, x = number(row.get(y_key)), number(row.get("integrator.dt"))
        if row.get("is_reference") or not (math.isfinite(x) and math.isfinite(y)):
            continue
        panel = scene_name(row) + (f", {row['collision.model']}" if "collision.model" in parameters else "")
        rest = [f"{key.split('.')[-1]}={row[key]}" for key in parameters if key in row
                and key not in ("integrator.dt", "collision.model") + INTEGRATOR_DETAIL + NEVER_IN_LABEL]
        name = ", ".join([str(row.get("integrator", "?"))] + rest)
        panels.setdefault(panel, {}).setdefault(name, []).append((x, y))
        colors[name] = integrator_color(row)
    if not panels:
        return None
    ncols = 2 if len(panels) > 1 else 1
    nrows = (len(panels) + ncols - 1) // ncols
    fig, axes = plt.subplots(nrows, ncols, figsize=(6.5 * ncols, 4 * nrows), squeeze=False,
                             sharey=True)
    markers = "osv^D<>p*h"
    for ax, (panel, groups) in zip(axes.ravel(), sorted(panels.items())):
        # Integrator by colour; the other swept values by marker and line style.
        variants = sorted({name.split(", ", 1)[-1] if ", " in name else "" for name in groups})
        for name, points in sorted(groups.items()):
            xs, ys = zip(*sorted(points))
            variant = variants.index(name.split(", ", 1)[-1] if ", " in name else "")
            ax.plot(xs, ys, marker=markers[variant % len(markers)],
                    ls=("-", "--", ":", "-.")[variant % 4], label=name, markersize=4,
                    color=colors[name])
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(panel, fontsize=9)
        ax.set_xlabel("dt [s]")
        ax.set_ylabel(ylabel)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=5.5)
    for ax in axes.ravel()[len(panels):]:
        ax.set_visible(False)
    return save(fig, out_dir, stem)


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
    # The first run of every scene first, then the others in order, at most MAX_SNAPSHOT_RUNS.
    first, seen = [], set()
    for row in rows:
        if row.get("scene") not in seen and not row.get("is_reference"):
            seen.add(row.get("scene"))
            first.append(row)
    ordered = first + [row for row in rows if row not in first and not row.get("is_reference")]
    for row in ordered:
        run = runfiles.run_dir(directory, row)
        if len(stems) >= MAX_SNAPSHOT_RUNS or not (run / "trace.csv").exists():
            continue
        trace = runfiles.trace_frames(runfiles.read_trace(run / "trace.csv"))
        frames = np.unique(np.append(np.nonzero(trace["event"])[0], len(trace["t"]) - 1))
        dummy = runfiles.read_table(run / "dummy.csv") if (run / "dummy.csv").exists() else None
        fig, axes = plt.subplots(2, len(frames), figsize=(2.6 * len(frames), 6.5), squeeze=False)
        # Zoom on the cloth: its extent over the shown frames, with a margin.
        shown = trace["x"][frames]
        lo, hi = shown.reshape(-1, 3).min(axis=0) - 0.08, shown.reshape(-1, 3).max(axis=0) + 0.08
        for col, k in enumerate(frames):
            for ax, (h, view) in zip(axes[:, col], (("x", "front"), ("z", "side"))):
                if dummy is not None:
                    ax.scatter(dummy[h], dummy["y"], s=0.5, c="0.8")
                x = trace["x"][k]
                fixed = trace["fixed"][k]
                axis = 0 if h == "x" else 2
                ax.scatter(x[~fixed, axis], x[~fixed, 1], s=1.5, c="tab:blue")
                ax.scatter(x[fixed, axis], x[fixed, 1], s=8, c="tab:red")
                ax.set_xlim(lo[axis], hi[axis])
                ax.set_ylim(lo[1], hi[1])
                ax.set_aspect("equal")
                ax.set_title(f"{view}, t = {trace['t'][k]:.3g} s", fontsize=8)
                ax.tick_params(labelsize=6)
        fig.suptitle(f"{row['id']} (front: x-y, side: z-y, object particles grey)", fontsize=8)
        stems.append(save(fig, out_dir, f"snapshots_{row['index']}"))
    return stems
