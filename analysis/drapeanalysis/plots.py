"""The report's figures in the style of style.py; each function saves PNG, SVG and PDF and
returns the file stem, or None when the table has nothing to plot. report.py calls them as
plots.<name>: the energy, error and step-size figures live in plots_energy.py, plots_error.py
and plots_vibration.py, accuracy against cost in plots_accuracy_cost.py, the data they plot in figure_data.py; this module names them all and
draws the simple ones (a metric against a swept value, the stable steps, the snapshots)."""
import math

import matplotlib.pyplot as plt

from . import snapshots as snapshot_views, style
from .figure_data import (INTEGRATOR_DETAIL, REPEAT_PARAMETER, label, method_label, number,
                          plotted_unit, scene_name, series, step, with_intervals)
from .plots_accuracy_cost import accuracy_cost
from .plots_energy import energy_by_scene, energy_vs_time
from .plots_error import restart_error_vs_horizon, work_precision
from .plots_vibration import vibration_vs_dt

# What report.py, viewer_pages.py and the tests call as plots.<name>, wherever it lives.
__all__ = ["INTEGRATOR_DETAIL", "accuracy_cost", "REPEAT_PARAMETER", "energy_by_scene", "energy_vs_time", "label",
           "line_plot", "method_label", "number", "restart_error_vs_horizon", "scene_name",
           "snapshots", "stable_dt", "step", "vibration_vs_dt", "with_intervals", "work_precision"]


def line_plot(out_dir, stem, rows, parameters, x_key, y_key, xlabel, ylabel, logx=True, logy=True,
              exclude=()):
    """One line per series of y against x, bars the 95 % interval over repeated runs; a length in
    mm (figure_data.plotted_unit)."""
    scale, ylabel = plotted_unit(y_key, ylabel)
    groups = {name: [(x, scale * y, scale * h, n, runs) for x, y, h, n, runs in points]
              for name, points in series(rows, parameters, x_key, y_key, exclude).items()}
    if not groups:
        return None
    fig, ax = plt.subplots(figsize=(6, 4))
    log_y = logy and all(p[1] > 0 for ps in groups.values() for p in ps)
    for k, (name, points) in enumerate(groups.items()):
        xs, ys, half, _, _ = zip(*points)
        bars = style.log_errorbar(ax, xs, ys, half, k, len(groups), dodge=logx, log_y=log_y,
                                  label=name, **style.variant_style(k))
        style.mark_partial(ax, points, bars.lines[0].get_color())
    ax.set_xscale("log" if logx else "linear")
    ax.set_yscale("log" if log_y else "linear")
    ax.set(xlabel=xlabel, ylabel=ylabel)
    ax.grid(True, which="both", alpha=0.3)
    style.legend_beside(ax)
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
