"""The report's figures in the style of style.py; each function saves PNG, SVG and PDF and
returns the file stem, or None when the table has nothing to plot."""
import math
from collections import Counter

import matplotlib.pyplot as plt
import numpy as np

from . import runfiles, snapshots as snapshot_views, stats, style
from .style import integrator_color

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


# The parameter that numbers an ensemble's repeats (experiments/sweep/experiment.cpp): never a
# series, its runs are one point.
REPEAT_PARAMETER = "perturbation.seed"


def with_intervals(points):
    """(x, mean y, 95 % half-width, n, N) for each x of (x, y) points, sorted by x: the N repeats
    of an ensemble as one point over its n finite values (half-width 0 for a single value); an x
    with no finite value is left out."""
    by_x = {}
    for x, y in points:
        by_x.setdefault(x, []).append(y)
    out = []
    for x in sorted(by_x):
        finite = [y for y in by_x[x] if math.isfinite(y)]
        if finite:
            _, mean, _, half = stats.interval(finite)
            out.append((x, mean, 0.0 if math.isnan(half) else half, len(finite), len(by_x[x])))
    return out


def intervals_by_name(groups):
    """with_intervals of each group's (x, y) points, leaving out a group with no finite value."""
    return {name: p for name, p in ((name, with_intervals(ps)) for name, ps in groups.items()) if p}


def mark_partial(ax, points, color="k"):
    """Writes "n of N" beside each point of with_intervals(points) that stands for fewer runs than
    its ensemble had (the others diverged or wrote no value), so that a point from one of two
    runs does not read as the ensemble's."""
    for x, y, _, n, runs in points:
        if n < runs:
            ax.annotate(f"{n} of {runs}", (x, y), textcoords="offset points", xytext=(4, 4),
                        fontsize=7, color=color)


def series(rows, parameters, x_key, y_key, exclude=()):
    """Points (x, mean y, 95 % half-width, n, N over the repeats: with_intervals) grouped by
    label, sorted by x, means of the finite values. x_key may be a function of the row."""
    groups = {}
    scenes = several_scenes(rows)
    for row in rows:
        x = number(x_key(row) if callable(x_key) else row.get(x_key))
        y = number(row.get(y_key))
        if math.isfinite(x) and not row.get("is_reference"):
            key = label(row, parameters, ((x_key,) if isinstance(x_key, str) else ()) + tuple(exclude)
                        + (REPEAT_PARAMETER,), with_scene=scenes)
            groups.setdefault(key, []).append((x, y))
    return intervals_by_name(groups)


def line_plot(out_dir, stem, rows, parameters, x_key, y_key, xlabel, ylabel, logx=True, logy=True,
              exclude=()):
    """One line per series of y against x, bars the 95 % interval over repeated runs."""
    groups = series(rows, parameters, x_key, y_key, exclude)
    if not groups:
        return None
    fig, ax = plt.subplots(figsize=(6, 4))
    log_y = logy and all(p[1] > 0 for ps in groups.values() for p in ps)
    for k, (name, points) in enumerate(groups.items()):
        xs, ys, half, _, _ = zip(*points)
        bars = style.log_errorbar(ax, xs, ys, half, k, len(groups), dodge=logx, log_y=log_y,
                                  label=name, **style.variant_style(k))
        mark_partial(ax, points, bars.lines[0].get_color())
    ax.set_xscale("log" if logx else "linear")
    ax.set_yscale("log" if log_y else "linear")
    ax.set(xlabel=xlabel, ylabel=ylabel)
    ax.grid(True, which="both", alpha=0.3)
    style.legend_beside(ax)
    return style.save(fig, out_dir, stem)


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
    fig, axes = plt.subplots(len(by_integrator), 1, figsize=(7.5, 2.4 * len(by_integrator)),
                             squeeze=False, sharex=True)
    scene_colors = {name: f"C{k}" for k, name in enumerate(sorted({scene_name(r) for r in rows}))}
    for ax, (name, runs) in zip(axes[:, 0], sorted(by_integrator.items())):
        steps = step_ranks(row for row, _ in runs)
        # The repeats of an ensemble share a style and one legend entry that counts them; a
        # run that did not finish is tagged, as its line stops where it diverged.
        named_by = [p for p in parameters if p != REPEAT_PARAMETER]
        texts = [label(row, named_by, INTEGRATOR_DETAIL, with_scene=scenes) + status_tag(row)
                 for row, _ in runs]
        counts, seen = Counter(texts), set()
        for (row, run), text in zip(runs, texts):
            energy = runfiles.read_energy(run / "energy.csv")
            total = energy["total"].to_numpy()
            rel = np.abs(total - total[0]) / max(abs(total[0]), 1e-300)
            shown = "_nolegend_" if text in seen else text + (f" ({counts[text]} runs)" if counts[text] > 1 else "")
            seen.add(text)
            ax.plot(energy["t"], np.maximum(rel, 1e-17), lw=0.9, ls=style.LINE_STYLES[steps[step(row)] % 6],
                    color=scene_colors[scene_name(row)], label=shown)
        ax.set_yscale("log")
        ax.set_ylim(bottom=1e-8)  # round-off at the first rows would squash the scale
        ax.set_title(name)
        ax.set_ylabel("|E - E0| / |E0|")
        style.legend_beside(ax)
    axes[-1, 0].set_xlabel("t [s]")
    return style.save(fig, out_dir, "energy_vs_time")


# Integrator keys that only qualify the method (its name and step already tell it apart).
INTEGRATOR_DETAIL = ("integrator.name", "integrator.table", "integrator.adaptive",
                     "integrator.linear_solver")


def status_tag(row):
    """" [diverged]" (or the other status) for a run that did not finish, "" otherwise."""
    return f" [{row.get('status')}]" if row.get("status") not in (None, "ok") else ""


def step(row):
    """A run's step size (inf when it has none)."""
    value = number(row.get("integrator.dt", row.get("dt")))
    return value if math.isfinite(value) else math.inf


def step_ranks(rows):
    """Rank of each step size among the runs (0 the smallest): the line style of a step."""
    return {dt: k for k, dt in enumerate(sorted({step(row) for row in rows}))}


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
    fig, axes = plt.subplots(len(by_scene), 1, figsize=(8, 2.8 * len(by_scene)), squeeze=False)
    for ax, (name, runs) in zip(axes[:, 0], by_scene.items()):
        ranks = {}  # step ranks per integrator: two steps of one method never look alike
        for row, _ in runs:
            if not row.get("is_reference"):
                ranks.setdefault(row.get("integrator"), []).append(row)
        ranks = {key: step_ranks(group) for key, group in ranks.items()}
        for row, run in runs:
            energy = runfiles.read_energy(run / "energy.csv")
            line = (dict(c="k", lw=1.4, ls="--", alpha=0.6, zorder=1) if row.get("is_reference") else
                    dict(lw=1.0, c=integrator_color(row),
                         ls=style.LINE_STYLES[ranks[row.get("integrator")][step(row)] % len(style.LINE_STYLES)]))
            text = method_label(row) + (" (reference)" if row.get("is_reference") else "") + status_tag(row)
            ax.plot(energy["t"], 1e3 * (energy["total"] - energy["total"].iloc[0]), **line,  # a repeat: no new legend entry
                    label=text if text not in ax.get_legend_handles_labels()[1] else "_nolegend_")
        ax.set_title(name)
        # One run's events, labelled (every run's would bury the labels): the reference's when
        # the scene has one, else the first run's; the caption says so.
        marked = next((row for row, _ in runs if row.get("is_reference")), runs[0][0])
        style.mark_events(ax, event_times(directory, marked))
        ax.set_ylabel("E(t) - E(0) [mJ]")
    style.legend_beside(axes[0, 0])
    axes[-1, 0].set_xlabel("t [s]")
    return style.save(fig, out_dir, "energy_by_scene")


def work_precision(out_dir, rows, parameters):
    """Error against the reference run vs right-hand-side evaluations and wall time, one row of
    panels per scene, one line per integrator (its steps joined; mean over repeats, 95 % bars).
    The error is the restart error after the events where the runs measured it
    (docs/analysis.md), else the final positions'."""
    error_key = ("restart_error_events" if any(math.isfinite(number(row.get("restart_error_events")))
                                               for row in rows) else "error_rms")
    if not any(math.isfinite(number(row.get(error_key))) for row in rows):
        return None
    by_scene = {}
    for row in rows:
        scene = by_scene.setdefault(scene_name(row), [])
        if not row.get("is_reference") and math.isfinite(number(row.get(error_key))):
            scene.append(row)
    fig, axes = plt.subplots(len(by_scene), 2, figsize=(10, 3.2 * len(by_scene)), squeeze=False,
                             sharey="row")
    for r, (name, scene_rows) in enumerate(by_scene.items()):
        for c, key in enumerate(("rhs_evals", "wall_seconds")):
            ax = axes[r, c]
            if not scene_rows:
                style.empty_note(ax, f"{name}: no run with an error against the reference\n"
                                     "(reference or runs diverged, or no reference)")
                continue
            # One point per method and step: the mean over the repeats, bars their 95 % interval.
            groups, colors = {}, {}
            for row in scene_rows:
                rest = label(row, parameters, ("integrator.dt", REPEAT_PARAMETER) + INTEGRATOR_DETAIL)
                key_name = str(row.get("integrator", "?")) + (f", {rest}" if rest != scene_name(row) else "")
                colors[key_name] = integrator_color(row)
                by_step = groups.setdefault(key_name, {}).setdefault(row.get("integrator.dt"), [])
                by_step.append((number(row.get(key)), number(row.get(error_key))))
            points = {}
            for series_name, by_step in sorted(groups.items()):
                points[series_name] = sorted(
                    (np.mean([x for x, _ in pairs]), *stats.interval([y for _, y in pairs])[1::2], dt)
                    for dt, pairs in by_step.items())
                xs, ys, half, _ = zip(*points[series_name])
                style.log_errorbar(ax, xs, ys, half, dodge=False, fmt="o-", label=series_name,
                                   color=colors[series_name])
            ax.set_xscale("log")
            ax.set_yscale("log")
            for series_name, series in points.items():  # step sizes, clear of each other
                style.place_labels(ax, [(x, y) for x, y, *_ in series], [f"{number(dt):.3g} s" if math.isfinite(number(dt)) else f"{dt}" for *_, dt in series],
                                   colors[series_name], half=[h for _, _, h, _ in series])
            ax.set_title(name)
            ax.set_xlabel("right-hand-side evaluations" if key == "rhs_evals" else "wall time [s]")
            ax.grid(True, which="both", alpha=0.3)
        axes[r, 0].set_ylabel("restart error after the events,\nfirst horizon [m]"
                              if error_key == "restart_error_events" else "RMS final position error [m]")
    style.legend_beside(axes[0, 1])
    return style.save(fig, out_dir, "work_precision")


def restart_error_vs_horizon(directory, out_dir, rows, parameters):
    """Restart error after the events against the horizon (docs/analysis.md, "Restart error"),
    one panel per scene, one line per method: the mean over its runs of each run's mean over its
    event branches, bars the 95 % interval over the runs."""
    panels, styles = {}, {}
    ranks = step_ranks(rows)
    for row in rows:
        path = runfiles.run_dir(directory, row) / "restart_error.csv"
        if row.get("is_reference") or not path.exists():
            continue
        branches = runfiles.read_restart_error(path)
        after = branches[(branches["events"] != "start") & (branches["status"] == "ok")]
        rest = label(row, parameters, ("integrator.dt", REPEAT_PARAMETER) + INTEGRATOR_DETAIL)
        name = method_label(row) + (f", {rest}" if rest != scene_name(row) else "")
        # Integrator by colour, its step by line style and marker (style.py).
        styles[name] = {"color": integrator_color(row), **style.variant_style(ranks[step(row)])}
        per_run = after.groupby("horizon")["error_rms"].mean()
        if per_run.empty:  # every branch after an event failed, or the run had no event
            continue
        panel = panels.setdefault(scene_name(row), {}).setdefault(name, {})
        for horizon, value in per_run.items():
            panel.setdefault(horizon, []).append(value)
    if not panels:
        return None
    fig, axes = plt.subplots(1, len(panels), figsize=(5.2 * len(panels), 3.6), squeeze=False, sharey=True)
    for ax, (scene, groups) in zip(axes[0], sorted(panels.items())):
        for k, (name, by_horizon) in enumerate(sorted(groups.items())):
            horizons = sorted(by_horizon)
            _, means, _, half = zip(*(stats.interval(by_horizon[h]) for h in horizons))
            style.log_errorbar(ax, horizons, means, half, k, len(groups), label=name, **styles[name])
        style.log_x_ticks_at(ax, sorted({h for by_horizon in groups.values() for h in by_horizon}))
        ax.set_yscale("log")
        ax.set_title(scene)
        ax.set_xlabel("horizon after the event [s]")
        ax.grid(True, which="both", alpha=0.3)
    axes[0, 0].set_ylabel("RMS error against the reference [m]")
    style.legend_below(fig, axes.ravel(), ncol=2)
    return style.save(fig, out_dir, "restart_error_vs_horizon")


def vibration_vs_dt(out_dir, rows, parameters, y_key="vibration_rms_final",
                    ylabel="vibration RMS, last 0.5 s [m]", stem="vibration_vs_dt"):
    """y against the step, one panel per scene and collision model (when swept), one line per
    integrator and the other swept values; the step axis spans all methods."""
    if "integrator.dt" not in parameters:
        return None
    panels, colors, references = {}, {}, {}
    for row in rows:
        panel = scene_name(row) + (f", {row['collision.model']}" if "collision.model" in parameters else "")
        groups = panels.setdefault(panel, {})
        y, x = number(row.get(y_key)), number(row.get("integrator.dt"))
        if row.get("is_reference"):  # its repeats: one line at their mean
            references.setdefault(panel, (method_label(row), []))[1].append(y)
            continue
        if not math.isfinite(x):
            continue
        rest = [f"{key.split('.')[-1]}={row[key]}" for key in parameters if key in row
                and key not in ("integrator.dt", "collision.model", REPEAT_PARAMETER) + INTEGRATOR_DETAIL
                + NEVER_IN_LABEL]
        name = ", ".join([str(row.get("integrator", "?"))] + rest)
        groups.setdefault(name, []).append((x, y))
        colors[name] = (integrator_color(row), style.INTEGRATOR_MARKERS.get(row.get("integrator"), "o"))
    # A method's points are the means of its finite values; one with none at all is left out.
    panels = {panel: intervals_by_name(groups) for panel, groups in panels.items()}
    if not any(panels.values()):
        return None
    ncols = 2 if len(panels) > 1 else 1
    nrows = (len(panels) + ncols - 1) // ncols
    fig, axes = plt.subplots(nrows, ncols, figsize=(5.2 * ncols, 3.4 * nrows), squeeze=False,
                             sharey=True)
    for ax, (panel, groups) in zip(axes.ravel(), sorted(panels.items())):
        ax.set_title(panel)
        if not groups:
            style.empty_note(ax, f"no finite {y_key}:\nruns diverged or wrote no trace")
            continue
        # Integrator by colour; the other swept values by marker and line style.
        variants = sorted({name.split(", ", 1)[-1] if ", " in name else "" for name in groups})
        for k, (name, points) in enumerate(sorted(groups.items())):
            xs, ys, half, _, _ = zip(*points)
            variant = variants.index(name.split(", ", 1)[-1] if ", " in name else "")
            color, marker = colors[name]
            style.log_errorbar(ax, xs, ys, half, k, len(groups), label=name, color=color, mfc="none",
                               mew=1.2, **{**style.variant_style(variant), "marker": marker})
            mark_partial(ax, points, color)
        reference_name, reference_ys = references.get(panel, ("", []))
        reference_y = stats.interval(reference_ys)[1]
        if math.isfinite(reference_y):
            ax.axhline(reference_y, c="k", lw=1.0, ls="--", label=f"{reference_name} (reference)")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set(xlabel="dt [s]", ylabel=ylabel)
        ax.grid(True, which="both", alpha=0.3)
    for ax in axes.ravel()[len(panels):]:
        ax.set_visible(False)
    style.legend_below(fig, axes.ravel(), ncol=3)
    return style.save(fig, out_dir, stem)


def stable_dt(out_dir, rows, parameters):
    """Largest stable value found by bisection, one bar per run."""
    found = [(label(row, parameters), number(row.get("stable_value"))) for row in rows]
    found = [(name, value) for name, value in found if math.isfinite(value)]
    if not found:
        return None
    fig, ax = plt.subplots(figsize=(7, 0.4 * len(found) + 1.5))
    names, values = zip(*found)
    ax.barh(range(len(found)), values)
    ax.set_yticks(range(len(found)), names)
    ax.set_xscale("log")
    ax.set_xlabel(f"largest stable {rows[0].get('bisect_parameter', 'dt')}")
    ax.grid(True, axis="x", which="both", alpha=0.3)
    return style.save(fig, out_dir, "stable_dt")


def snapshots(directory, out_dir, rows):
    """Shaded front and side views of every scene, methods side by side (snapshots.py)."""
    by_scene = {}
    for row in rows:
        by_scene.setdefault(scene_name(row), []).append(row)
    return [stem for scene, scene_rows in by_scene.items()
            for stem in snapshot_views.scene_figures(directory, out_dir, scene, scene_rows)]
