"""The error figures against the reference run (docs/analysis.md, "Figures" and "Restart
error"): error against cost (`work_precision`) and the restart error against its horizon
(`restart_error_vs_horizon`), lengths in mm as in the report's tables."""
import math
import warnings

import matplotlib.pyplot as plt
import numpy as np

from . import runfiles, stats, style, table_columns
from .figure_data import (INTEGRATOR_DETAIL, REPEAT_PARAMETER, label, method_label,
                          number, plotted_unit, scene_name, step, step_ranks)
from .run_series import read_run_restart_error
from .style import integrator_color


def step_text(dt):
    """A step as a label: "0.0333 s"."""
    return f"{number(dt):.3g} s" if math.isfinite(number(dt)) else str(dt)


def work_precision(out_dir, rows, parameters):
    """Error against the reference run vs right-hand-side evaluations and wall time, one row of
    panels per scene, one line per integrator (its steps joined; mean over repeats, 95 % bars).
    The error is the restart error after the events where the runs measured it
    (docs/analysis.md), else the final positions', in mm. A method run at one step names it in
    the legend; only the points of a method with several steps are labelled with theirs, where
    they overlap least (labels crowded the panels)."""
    error_key = ("restart_error_events" if any(math.isfinite(number(row.get("restart_error_events")))
                                               for row in rows) else "error_rms")
    if not any(math.isfinite(number(row.get(error_key))) for row in rows):
        return None
    by_scene = {}
    for row in rows:
        scene = by_scene.setdefault(scene_name(row), [])
        if not row.get("is_reference") and math.isfinite(number(row.get(error_key))):
            scene.append(row)
    scale, ylabel = plotted_unit(error_key, "restart error after the events,\nfirst horizon [m]"
                                 if error_key == "restart_error_events" else "RMS final position error [m]")
    fig, axes = plt.subplots(len(by_scene), 2, figsize=(8, 3.2 * len(by_scene)), squeeze=False,
                             sharey="row")
    labelled = []  # (axes, points, colour) of the methods with several steps
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
                by_step.append((number(row.get(key)), scale * number(row.get(error_key))))
            points = {}
            for series_name, by_step in sorted(groups.items()):
                points[series_name] = sorted(
                    (np.mean([x for x, _ in pairs]), *stats.interval([y for _, y in pairs])[1::2], dt)
                    for dt, pairs in by_step.items())
                xs, ys, half, steps = zip(*points[series_name])
                one_step = f", dt={step_text(steps[0])}" if len(steps) == 1 else ""
                style.log_errorbar(ax, xs, ys, half, dodge=False, fmt="o-", label=series_name + one_step,
                                   color=colors[series_name])
            ax.set_xscale("log")
            ax.set_yscale("log")
            labelled += [(ax, series, colors[method]) for method, series in points.items()
                         if len(series) > 1]
            ax.set_title(name)
            ax.set_xlabel("right-hand-side evaluations" if key == "rhs_evals" else "wall time [s]")
            ax.grid(True, which="both", alpha=0.3)
        axes[r, 0].set_ylabel(ylabel)
    # Room above the highest bar for the step labels: at the axis' top they would cross a
    # neighbour's bar for want of a free spot.
    for row_axes in axes:
        if any(ax is labelled_ax for ax in row_axes for labelled_ax, _, _ in labelled):
            low, high = row_axes[0].get_ylim()
            row_axes[0].set_ylim(low, high * 2)
    style.legend_below(fig, axes.ravel(), ncol=2)
    # Labels are placed on the final layout: placed before it, on wider panels, they overlapped.
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        fig.tight_layout()
    for ax, series, color in labelled:  # step sizes, clear of each other
        style.place_labels(ax, [(x, y) for x, y, *_ in series], [step_text(dt) for *_, dt in series],
                           color, half=[h for _, _, h, _ in series], joined=True)
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
        branches = read_run_restart_error(path.parent)
        after = branches[(branches["events"] != "start") & (branches["status"] == "ok")]
        rest = label(row, parameters, ("integrator.dt", REPEAT_PARAMETER) + INTEGRATOR_DETAIL)
        name = method_label(row) + (f", {rest}" if rest != scene_name(row) else "")
        # Integrator by colour, its step by line style and marker (style.py).
        styles[name] = {"color": integrator_color(row), **style.variant_style(ranks[step(row)])}
        per_run = table_columns.shown_value("restart_error_events",
                                            after.groupby("horizon")["error_rms"].mean())
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
    axes[0, 0].set_ylabel("RMS error against the reference [mm]")
    style.legend_below(fig, axes.ravel(), ncol=2)
    return style.save(fig, out_dir, "restart_error_vs_horizon")
