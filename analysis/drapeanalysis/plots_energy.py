"""The energy figures (docs/analysis.md, "Figures"): the relative energy change of every run per
integrator (`energy_vs_time`) and E(t) - E(0) of every method per scene, one small panel per
integrator with the reference in each (`energy_by_scene`). A run that did not finish is drawn as
far as it got, ends in an x and says where it stopped in the legend."""
import math
from collections import Counter

import matplotlib.pyplot as plt
import matplotlib.transforms
import numpy as np
from matplotlib.lines import Line2D

from . import runfiles, style
from .figure_data import (INTEGRATOR_DETAIL, REPEAT_PARAMETER, event_times, method_label,
                          number, scene_name, step, step_ranks)

# The relative change's floor: round-off at the first rows would squash the log scale.
REL_FLOOR = 1e-8
# Small multiples of energy_by_scene: panels a row.
COLUMNS = 3


def stopped_tag(row):
    """" (diverged at t = 0.006 s)" (or the run's other status) for a run that did not finish,
    "" otherwise."""
    if row.get("status") in (None, "ok"):
        return ""
    return f" ({row.get('status')} at t = {number(row.get('sim_time')):.3g} s)"


def draw_run(ax, t, y, stopped, **line):
    """A run's curve; one that did not finish also ends in an x at its last value, so that a run
    of one row (diverged in its first steps) is seen at all."""
    if stopped:  # the x on the line's last point, so that its legend entry shows it too
        line = {**line, "marker": style.FAILED_MARK, "markevery": [len(t) - 1], "ms": 7, "mew": 1.5,
                "clip_on": False}
    ax.plot(t, y, **line)


def varying(rows, keys):
    """The keys of `keys` whose values differ among `rows` (the others go into a title)."""
    return [key for key in keys if len({str(row.get(key)) for row in rows}) > 1]


def short_label(row, keys):
    """"dt=0.01, max_newton_iters=10": the run's step and its values of `keys`."""
    parts = [f"dt={row.get('integrator.dt', row.get('dt'))}"]
    return ", ".join(parts + [f"{key.split('.')[-1]}={row[key]}" for key in keys if key in row])


def energy_vs_time(directory, out_dir, rows, parameters):
    """Relative energy change |E(t) - E(0)| / |E(0)| from the start (manipulations and damping
    included: not an error) of every run, one panel per integrator, colour per scene (one legend
    above the figure, read first), line style per step; a panel's legend names the steps and
    counts the runs, its constant values go into its title."""
    by_integrator = {}
    for row in rows:
        run = runfiles.run_dir(directory, row)
        if (run / "energy.csv").exists() and not row.get("is_reference"):
            by_integrator.setdefault(row.get("integrator", "?"), []).append((row, run))
    if not by_integrator:
        return None
    fig, axes = plt.subplots(len(by_integrator), 1, figsize=(7.0, 1.7 * len(by_integrator) + 0.6),
                             squeeze=False, sharex=True)
    scene_colors = {name: f"C{k}" for k, name in enumerate(sorted({scene_name(r) for r in rows}))}
    keys = [p for p in parameters if p not in (REPEAT_PARAMETER, "integrator.dt") + INTEGRATOR_DETAIL]
    for ax, (name, runs) in zip(axes[:, 0], sorted(by_integrator.items())):
        steps = step_ranks(row for row, _ in runs)
        shown = varying([row for row, _ in runs], keys)
        first = runs[0][0]
        constant = [f"{k.split('.')[-1]}={first[k]}" for k in keys if k not in shown and k in first]
        tags = [stopped_tag(row) for row, _ in runs]
        texts = [short_label(row, shown) + tag for (row, _), tag in zip(runs, tags)]
        counts, entries = Counter(texts), {}
        for (row, run), text, tag in zip(runs, texts, tags):
            energy = runfiles.read_energy(run / "energy.csv")
            total = energy["total"].to_numpy()
            rel = np.maximum(np.abs(total - total[0]) / max(abs(total[0]), 1e-300), REL_FLOOR)
            line = dict(lw=0.9, ls=style.LINE_STYLES[steps[step(row)] % len(style.LINE_STYLES)],
                        color=scene_colors[scene_name(row)])
            draw_run(ax, energy["t"].to_numpy(), rel, bool(tag), **line)
            # The legend tells steps apart (line style), not scenes (the colours, above the figure).
            entries.setdefault(text + (f" ({counts[text]} runs)" if counts[text] > 1 else ""),
                               Line2D([], [], color="0.3", lw=0.9, ls=line["ls"],
                                      marker=style.FAILED_MARK if tag else ""))
        ax.set_yscale("log")
        ax.set_ylim(bottom=REL_FLOOR)
        ax.set_title(name + (f" ({', '.join(constant)})" if constant else ""))
        ax.set_ylabel("|E - E0| / |E0|")
        ax.legend(list(entries.values()), list(entries), loc="upper left", bbox_to_anchor=(1.01, 1.0),
                  borderaxespad=0, frameon=False)
    axes[-1, 0].set_xlabel("t [s]")
    fig.legend([Line2D([], [], color=c) for c in scene_colors.values()], list(scene_colors),
               loc="lower center", bbox_to_anchor=(0.5, 1.0), ncol=2, frameon=False)
    return style.save(fig, out_dir, "energy_vs_time")


def energy_by_scene(directory, out_dir, rows, parameters):
    """Total energy E(t) - E(0) of every method, a block of small panels per scene, one panel per
    integrator (its steps by line style) sharing the axes, the reference run dashed black in each
    and the events of one run marked (labelled in the block's first panel): in driven, damped
    scenes energy is not conserved, so the methods are compared with each other."""
    by_scene = {}
    for row in rows:
        run = runfiles.run_dir(directory, row)
        if (run / "energy.csv").exists():
            by_scene.setdefault(scene_name(row), []).append((row, run))
    if not by_scene or not any(row.get("events") for row in rows):
        return None
    blocks = {scene: sorted({str(row.get("integrator", "?")) for row, _ in runs
                             if not row.get("is_reference")}) for scene, runs in by_scene.items()}
    columns = min(COLUMNS, max(len(names) for names in blocks.values()))
    heights = [max(1, math.ceil(len(names) / columns)) for names in blocks.values()]
    fig = plt.figure(figsize=(3.3 * columns, 3.0 * sum(heights) + 0.5 * len(blocks)),
                     layout="constrained")
    for subfig, (scene, runs), height in zip(fig.subfigures(len(blocks), 1, height_ratios=heights,
                                                            squeeze=False)[:, 0], by_scene.items(), heights):
        subfig.suptitle(scene, fontsize=style.RC["axes.titlesize"] + 1)
        names = blocks[scene]
        axes = subfig.subplots(height, columns, sharex=True, sharey=True, squeeze=False).ravel()
        reference = [(row, run) for row, run in runs if row.get("is_reference")]
        for ax, name in zip(axes, names):
            own = [(row, run) for row, run in runs
                   if str(row.get("integrator", "?")) == name and not row.get("is_reference")]
            energy_panel(ax, own, reference, name)
        for ax in axes[len(names):]:
            ax.set_visible(False)
        # The reference's events, else the first run's: labelled in the first panel (mark_events
        # draws its lines too), lines only in the others.
        events = event_times(directory, (reference or runs)[0][0])
        style.mark_events(axes[0], events)
        for ax in axes[1:len(names)]:
            for t, _ in events:
                ax.axvline(t, c="0.45", lw=0.7, ls=":")
        for ax in axes[::columns]:
            ax.set_ylabel("E(t) - E(0) [mJ]")
    return style.save(fig, out_dir, "energy_by_scene")


def energy_panel(ax, runs, reference, name):
    """One integrator's runs of a scene (line style per step) over the reference (dashed black),
    legend under the panel."""
    ranks = step_ranks(row for row, _ in runs)
    for row, run in reference + runs:
        energy = runfiles.read_energy(run / "energy.csv")
        is_reference = bool(row.get("is_reference"))
        line = (dict(color="k", lw=1.2, ls="--", alpha=0.6, zorder=1) if is_reference else
                dict(lw=1.0, color=style.integrator_color(row),
                     ls=style.LINE_STYLES[ranks[step(row)] % len(style.LINE_STYLES)]))
        tag = stopped_tag(row)
        text = method_label(row) + (" (reference)" if is_reference else "") + tag
        shown = text not in ax.get_legend_handles_labels()[1]  # a repeat: no new entry
        draw_run(ax, energy["t"].to_numpy(), 1e3 * (energy["total"] - energy["total"].iloc[0]).to_numpy(),
                 bool(tag), label=text if shown else "_nolegend_", **line)
    ax.set_title(name)
    # Every panel reads alone: its own time axis, its legend under it (clear of the tick labels
    # and the axis label, 30 points), never over another panel's curves.
    ax.set_xlabel("t [s]")
    ax.xaxis.set_tick_params(labelbottom=True)
    under = matplotlib.transforms.offset_copy(ax.transAxes, ax.figure, y=-30, units="points")
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, 0.0), bbox_transform=under, frameon=False)
