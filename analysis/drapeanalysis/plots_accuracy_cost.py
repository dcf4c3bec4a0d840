"""Accuracy against cost (docs/figures.md, `accuracy_cost`): each method at each of its settings
as one point, x its CPU (else wall) seconds per simulated second, y its restart error after the
hold (the first horizon, and a later one in a second panel), the marker's size its vibration
after the hold; mean over an ensemble's runs, bars their 95 % Student-t interval
(stats.interval). A setting's points are joined along its step and its solver's work per step."""
import math
import re
import warnings

import matplotlib.pyplot as plt

from . import stats, style, table_columns
from .figure_data import INTEGRATOR_DETAIL, NEVER_IN_LABEL, REPEAT_PARAMETER, number, scene_name
from .plots_error import step_text

# The columns plotted (metrics.restart_error, metrics.vibration): y of the first panel, y of the
# later panels (`restart_error_after_hold_<ms>ms`), the marker's size.
FIRST_ERROR = "restart_error_after_hold"
LATER_ERROR = re.compile(r"restart_error_after_hold_(\d+)ms")
VIBRATION = "vibration_rms_after_hold"
# Simulated time passes as fast as wall time: x = 1.
REAL_TIME = 1.0
# Marker sizes (points) of the smallest and largest vibration in the figure.
SIZE_RANGE = (4.0, 14.0)
# The keys a setting's points are joined along: the step and the solver's work per step (xpbd's
# substeps, projective dynamics' and vbd's iterations); every other integrator key makes a
# setting of its own.
ALONG = ("integrator.dt", "integrator.substeps", "integrator.iterations")
# The cost's columns (summary.json, docs/outputs.md), the first the table has: the stepping's CPU
# time, which other jobs on a shared machine leave alone, else its wall time.
COSTS = (("cpu_seconds", "CPU"), ("wall_seconds", "wall"))


def cost_column(rows):
    """(column, name) of COSTS: the first with a finite value in some row."""
    for column, name in COSTS:
        if any(math.isfinite(number(row.get(column))) for row in rows):
            return column, name
    return COSTS[-1]


def cost(row, column="cpu_seconds"):
    """Seconds of `column` per simulated second: the run's time over the time it simulated (nan
    for a run that simulated none or has no such time)."""
    seconds, simulated = number(row.get(column)), number(row.get("sim_time"))
    return seconds / simulated if simulated > 0 else math.nan


def later_error_column(rows):
    """The restart-error-after-the-hold column at the largest horizon after the first (None when
    the runs measured only one)."""
    found = {int(m.group(1)): key for row in rows for key in row
             if (m := LATER_ERROR.fullmatch(key)) and math.isfinite(number(row[key]))}
    return found[max(found)] if found else None


def setting_name(row, parameters):
    """The method without its step and work per step (ALONG): integrator and its other swept
    values (a case that does not set a key leaves it out)."""
    skip = ALONG + (REPEAT_PARAMETER,) + INTEGRATOR_DETAIL + NEVER_IN_LABEL
    rest = [f"{key.split('.')[-1]}={row[key]}" for key in parameters
            if key not in skip and key.startswith("integrator.") and row.get(key) is not None
            and not (isinstance(row[key], float) and math.isnan(row[key]))]
    return ", ".join([str(row.get("integrator", "?"))] + rest)


def _mean_half(values):
    """(mean, 95 % half-width: 0 for one value) of finite values."""
    _, mean, _, half = stats.interval(values)
    return mean, 0.0 if math.isnan(half) else half


def along_text(key, value, named=False):
    """A value of an ALONG key as a label: a step "0.0333 s" ("dt=0.0333 s" when `named`), a
    count "substeps=10"."""
    if key == "integrator.dt":
        return ("dt=" if named else "") + step_text(value)
    return f"{key.split('.')[-1]}={int(value) if float(value).is_integer() else value}"


def _label_along(pts):
    """Gives each point of a setting `text`, its ALONG values that vary between the points, and
    `fixed`, the values they share (named, for the legend)."""
    present = [k for k in ALONG if any(math.isfinite(p["along"][k]) for p in pts)]
    varying = [k for k in present if len({p["along"][k] for p in pts}) > 1]
    for p in pts:
        p["text"] = ", ".join(along_text(k, p["along"][k]) for k in varying)
        p["fixed"] = ", ".join(along_text(k, p["along"][k], True) for k in present if k not in varying)


def points(rows, parameters, y_key, column="cpu_seconds"):
    """{scene: {setting: [point, ...] along its ALONG values}}, a point a dict: along (its
    ALONG values), text and fixed (_label_along), x and x_half (cost in `column`), y and y_half
    (y_key in mm), vibration (mm, mean), n (runs with a y) and runs (the ensemble's size). A
    point none of whose runs has a y has n = 0, x the mean cost of its runs (how far they got),
    `failed` the number that did not finish."""
    groups = {}
    for row in rows:
        if row.get("is_reference"):
            continue
        # -inf for a key the run does not set: a value that sorts and compares equal.
        along = tuple(v if math.isfinite(v := number(row.get(k))) else -math.inf for k in ALONG)
        groups.setdefault((scene_name(row), setting_name(row, parameters), along), []).append(row)
    out = {}
    for (scene, setting, along), runs in sorted(groups.items()):
        with_y = [r for r in runs if math.isfinite(number(r.get(y_key))) and math.isfinite(cost(r, column))]
        measured = with_y or [r for r in runs if math.isfinite(cost(r, column))]
        if not measured:
            continue
        x, x_half = _mean_half([cost(r, column) for r in measured])
        y, y_half = _mean_half([table_columns.shown_value("restart_error_events", number(r.get(y_key)))
                                for r in with_y])
        vibration = stats.interval([table_columns.shown_value("vibration_rms_events", number(r.get(VIBRATION)))
                                    for r in with_y])[1]
        out.setdefault(scene, {}).setdefault(setting, []).append(
            {"along": dict(zip(ALONG, along)), "x": x, "x_half": x_half, "y": y, "y_half": y_half,
             "vibration": vibration, "n": len(with_y), "runs": len(runs), "integrator": runs[0].get("integrator"),
             "failed": sum(r.get("status") not in (None, "ok") for r in runs)})
    for settings in out.values():
        for pts in settings.values():
            _label_along(pts)
    return out


def marker_size(vibration, low, high):
    """A marker size (points) growing with the vibration's logarithm from low to high."""
    if not math.isfinite(vibration) or vibration <= 0:
        return SIZE_RANGE[0]
    if not high > low:
        return sum(SIZE_RANGE) / 2
    share = math.log(vibration / low) / math.log(high / low)
    return SIZE_RANGE[0] + share * (SIZE_RANGE[1] - SIZE_RANGE[0])


def reference_cost(rows, scene, column="cpu_seconds"):
    """(mean cost in `column`, label) of the scene's reference runs, or None."""
    runs = [r for r in rows if r.get("is_reference") and scene_name(r) == scene]
    costs = [cost(r, column) for r in runs if math.isfinite(cost(r, column))]
    if not costs:
        return None
    return sum(costs) / len(costs), f"reference: {runs[0].get('integrator')} dt={step_text(runs[0].get('integrator.dt'))}"


def _draw_panel(ax, settings, vib_range):
    """One panel: a line per setting through its steps, markers sized by vibration, bars both
    ways (the cost's lighter: time on a shared machine scatters), diverged points as x on the
    floor. Returns the labels to place, (points, colour, texts): a setting's ALONG values where
    it has several points, else its values where its integrator has other settings (same colour
    and marker)."""
    labelled = []
    per_integrator = {}
    for pts in settings.values():
        per_integrator[pts[0]["integrator"]] = per_integrator.get(pts[0]["integrator"], 0) + 1
    for setting, pts in sorted(settings.items()):
        row = {"integrator": pts[0]["integrator"]}
        color, marker = style.integrator_color(row), style.integrator_marker(row)
        drawn = [p for p in pts if p["n"]]
        one_point = len(pts) == 1
        fixed = f", {pts[0]['fixed']}" if pts[0].get("fixed") else ""
        name = f"{setting}{fixed} (n = {max(p['runs'] for p in pts)})"
        if drawn:
            bars = style.log_errorbar(ax, [p["x"] for p in drawn], [p["y"] for p in drawn],
                                      [p["y_half"] for p in drawn], dodge=False, fmt="-", color=color,
                                      xerr=[p["x_half"] for p in drawn], lw=1.0, elinewidth=0.8)
            bars.lines[2][0].set_alpha(0.4)
            for p in drawn:
                ax.plot(p["x"], p["y"], ls="none", marker=marker, color=color, mec="k", mew=0.6,
                        ms=marker_size(p["vibration"], *vib_range), zorder=3)
            ax.plot([], [], marker=marker, color=color, mec="k", mew=0.6, label=name)
            style.mark_partial(ax, [(p["x"], p["y"], p["y_half"], p["n"], p["runs"]) for p in drawn], color)
            if not one_point:
                labelled.append((drawn, color, [p["text"] for p in drawn]))
            elif per_integrator[pts[0]["integrator"]] > 1:
                labelled.append((drawn, color, [setting.partition(", ")[2] or setting]))
        # At the cost its runs reached, not dodged: no two settings share a cost by construction.
        style.mark_failed(ax, [(p["x"], ("" if one_point else f"{p['text']}: ")
                                + (f"diverged ({p['failed']} of {p['runs']})" if p["failed"]
                                   else f"no value ({p['runs']} of {p['runs']})")) for p in pts if not p["n"]],
                          color)
        if not drawn:
            ax.plot([], [], ls="none", marker=style.FAILED_MARK, color=color, label=name)
    return labelled


def accuracy_cost(out_dir, rows, parameters):
    """Restart error after the hold against CPU seconds per simulated second (wall seconds for a
    table without CPU times, cost_column), one row of panels per scene: the first horizon, then
    the largest later one; the real-time line x = 1 and the reference's cost dashed; the
    marker's size the vibration after the hold. None without a run with both a cost and an
    error after a hold."""
    columns = [FIRST_ERROR] + ([later] if (later := later_error_column(rows)) else [])
    cost_key, cost_name = cost_column(rows)
    panels = [points(rows, parameters, key, cost_key) for key in columns]
    if not any(p["n"] for scene in panels[0].values() for pts in scene.values() for p in pts):
        return None
    vibrations = [p["vibration"] for panel in panels for scene in panel.values() for pts in scene.values()
                  for p in pts if math.isfinite(p["vibration"]) and p["vibration"] > 0]
    vib_range = (min(vibrations), max(vibrations)) if vibrations else (1.0, 1.0)
    scenes = sorted(panels[0])
    fig, axes = plt.subplots(len(scenes), len(columns), figsize=(5.0 * len(columns), 3.8 * len(scenes)),
                             squeeze=False, sharex=True)
    labelled = []
    for r, scene in enumerate(scenes):
        for c, key in enumerate(columns):
            ax = axes[r, c]
            labelled += [(ax, *item) for item in _draw_panel(ax, panels[c].get(scene, {}), vib_range)]
            ax.axvline(REAL_TIME, color="k", lw=1.0, ls="-.", label="real time (x = 1)")
            reference = reference_cost(rows, scene, cost_key)
            if reference:
                ax.axvline(reference[0], color="0.4", lw=1.0, ls="--", label=reference[1])
            horizon = ("one frame (the first horizon) after the hold" if c == 0
                       else f"{LATER_ERROR.fullmatch(key).group(1)} ms after the hold")
            ax.set_title(f"{scene}: {horizon}" if len(scenes) > 1 else horizon, fontsize=style.MIN_FONT + 1)
            ax.margins(0.12)  # the largest markers clear of the frame
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_xlabel(f"{cost_name} seconds per simulated second (real time = 1)")
            ax.grid(True, which="both", alpha=0.3)
        axes[r, 0].set_ylabel("restart error after the hold [mm]")
    _include_real_time(axes)
    _size_legend(axes[0, 0], vib_range)
    style.legend_below(fig, axes.ravel(), ncol=2)
    fig.suptitle("a point: the mean over a setting's n runs; bars: their 95 % Student-t interval; "
                 "marker size: vibration after the hold", fontsize=style.MIN_FONT + 1)
    with warnings.catch_warnings():  # labels are placed on the final layout (place_labels)
        warnings.simplefilter("ignore")
        fig.tight_layout()
    for ax, drawn, color, texts in labelled:
        style.place_labels(ax, [(p["x"], p["y"]) for p in drawn], texts, color,
                           half=[p["y_half"] for p in drawn], joined=len(drawn) > 1)
    return style.save(fig, out_dir, "accuracy_cost")


def _include_real_time(axes):
    """Widens the shared x axis to show the real-time line with a margin on both sides."""
    low, high = axes[0, 0].get_xlim()
    axes[0, 0].set_xlim(min(low, REAL_TIME / 2), max(high, REAL_TIME * 2))


def _size_legend(ax, vib_range):
    """Legend entries for the smallest and largest vibration's marker size."""
    low, high = vib_range
    for value in sorted({low, high}):
        ax.plot([], [], ls="none", marker="o", color="0.6", mec="k", mew=0.6,
                ms=marker_size(value, low, high), label=f"vibration after the hold {value:.3g} mm")
