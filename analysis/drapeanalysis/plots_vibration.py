"""A per-run metric against the step size (`vibration_vs_dt`, `vibration_events_vs_dt`,
`contact_switch_vs_dt`; docs/analysis.md, "Figures"): one panel per scene and collision model,
the steps at which a method has no value at all kept on the axis and marked, lengths in mm."""
import math

import matplotlib.pyplot as plt

from . import stats, style
from .figure_data import (INTEGRATOR_DETAIL, NEVER_IN_LABEL, REPEAT_PARAMETER, intervals_by_name,
                          method_label, number, plotted_unit, scene_name)
from .style import integrator_color

# What a panel says when every run's value is 0 (a log axis would be empty).
ALL_ZERO_NOTES = {"contact_switch_rate_final": "no contact switches in any run"}


def failed_steps(points, statuses):
    """(x, "diverged (k of N)") for each x of (x, y) `points` with no finite y, k of its N runs
    not "ok" in `statuses` (one a point); "no value (N of N)" when all of them finished."""
    by_x = {}
    for (x, y), status in zip(points, statuses):
        by_x.setdefault(x, []).append((y, status))
    out = []
    for x, runs in sorted(by_x.items()):
        if not any(math.isfinite(y) for y, _ in runs):
            failed = sum(status not in (None, "ok") for _, status in runs)
            out.append((x, f"diverged ({failed} of {len(runs)})" if failed
                        else f"no value ({len(runs)} of {len(runs)})"))
    return out


def vibration_vs_dt(out_dir, rows, parameters, y_key="vibration_rms_final",
                    ylabel="vibration RMS, last 0.5 s [m]", stem="vibration_vs_dt"):
    """y against the step, one panel per scene and collision model (when swept), one line per
    integrator and the other swept values; the step axis spans all methods, and a step where a
    method has no value (its runs diverged) is an x on the panel's floor that says so. A log y
    axis when every value is above 0, else a linear one (all 0: the panel says so)."""
    if "integrator.dt" not in parameters:
        return None
    scale, ylabel = plotted_unit(y_key, ylabel)
    panels, statuses, colors, references = {}, {}, {}, {}
    for row in rows:
        panel = scene_name(row) + (f", {row['collision.model']}" if "collision.model" in parameters else "")
        groups = panels.setdefault(panel, {})
        y, x = scale * number(row.get(y_key)), number(row.get("integrator.dt"))
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
        statuses.setdefault((panel, name), []).append(row.get("status"))
        colors[name] = (integrator_color(row), style.integrator_marker(row))
    failures = {(panel, name): failed_steps(points, statuses[panel, name])
                for panel, groups in panels.items() for name, points in groups.items()}
    # A method's points are the means of its finite values; its steps with none are failures.
    drawn = {panel: intervals_by_name(groups) for panel, groups in panels.items()}
    if not any(drawn.values()) and not any(failures.values()):
        return None
    values = [y for groups in drawn.values() for ps in groups.values() for _, y, *_ in ps]
    # A log axis needs a positive value to stand on: an all-diverged figure has none.
    log_y = bool(values) and all(y > 0 for y in values)
    ncols = 2 if len(panels) > 1 else 1
    nrows = (len(panels) + ncols - 1) // ncols
    fig, axes = plt.subplots(nrows, ncols, figsize=(5.2 * ncols, 3.4 * nrows), squeeze=False,
                             sharey=True)
    for ax, panel in zip(axes.ravel(), sorted(panels)):
        ax.set_title(panel)
        names = sorted(panels[panel])
        # Integrator by colour; the other swept values by marker and line style.
        variants = sorted({name.split(", ", 1)[-1] if ", " in name else "" for name in names})
        for k, name in enumerate(names):
            color, marker = colors[name]
            variant = style.variant_style(variants.index(name.split(", ", 1)[-1] if ", " in name else ""))
            if name in drawn[panel]:
                points = drawn[panel][name]
                xs, ys, half, _, _ = zip(*points)
                style.log_errorbar(ax, xs, ys, half, k, len(names), log_y=log_y, label=name,
                                   color=color, mfc="none", mew=1.2, **{**variant, "marker": marker})
                style.mark_partial(ax, points, color)
            style.mark_failed(ax, failures[panel, name], color, k, len(names))
        reference_name, reference_ys = references.get(panel, ("", []))
        reference_y = stats.interval(reference_ys)[1]
        if math.isfinite(reference_y):
            ax.axhline(reference_y, c="k", lw=1.0, ls="--", label=f"{reference_name} (reference)")
        # Said in the panel, its step axis kept: the marks above show the steps that failed.
        note = (f"no finite {y_key}:\nevery run diverged or wrote no trace" if not drawn[panel] else
                ALL_ZERO_NOTES.get(y_key, f"{y_key} is 0 in every run") if not any(values) else "")
        if note:
            ax.text(0.5, 0.5, note, transform=ax.transAxes, ha="center", va="center", color="0.3")
        ax.set_xscale("log")
        ax.set_yscale("log" if log_y else "linear")
        ax.set(xlabel="dt [s]", ylabel=ylabel)
        ax.grid(True, which="both", alpha=0.3)
    if not log_y and all(y >= 0 for y in values):
        # A non-negative metric on a linear axis starts at 0: all zero, matplotlib would centre
        # the axis on 0 and show negative ticks.
        axes[0, 0].set_ylim(0, None if any(values) else 1)
    for ax in axes.ravel()[len(panels):]:
        ax.set_visible(False)
    if any(failures.values()):
        axes[0, 0].plot([], [], ls="none", marker=style.FAILED_MARK, color="0.3",
                        label="no value at this step (runs diverged)")
    style.legend_below(fig, axes.ravel(), ncol=3)
    return style.save(fig, out_dir, stem)
