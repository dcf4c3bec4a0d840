"""The report's summary (docs/analysis.md, Ensemble statistics): the method x scene tables of
the main metrics, as Student-t 95 % intervals of the mean over each method's repeats, and the
runs that did not finish, named before any number so that a reader does not take a dash or a
short ensemble for a result."""
import html
import math

import pandas as pd

from . import plots, stats

# The statuses of a run that ran to its end; any other (docs/outputs.md: diverged, failed; an
# experiment's error, crashed) left no comparable metrics.
FINISHED = "ok"
# How many unfinished runs the banner lists before it folds the list away.
BANNER_ROWS = 8

# The summary's method x scene tables: column, title, unit, scale to that unit.
SUMMARY_METRICS = (
    ("vibration_rms_events", "Vibration after the manipulations (largest event window)", "mm", 1e3),
    ("vibration_rms_after_hold", "Vibration after a hold", "mm", 1e3),
    ("vibration_rms_after_release", "Vibration after a release", "mm", 1e3),
    ("vibration_rms_after_attach", "Vibration after an attach", "mm", 1e3),
    ("vibration_rms_after_attach_fixed", "Vibration after an attached particle is fixed", "mm", 1e3),
    ("vibration_rms_after_map", "Vibration after a map", "mm", 1e3),
    ("vibration_rms_final", "Vibration over the last 0.5 s", "mm", 1e3),
    ("slow_motion_rms_final", "Slow motion over the last 0.5 s", "mm", 1e3),
    ("restart_error_start", "Restart error at the first horizon after the start", "mm", 1e3),
    ("restart_error_events", "Restart error at the first horizon after the events (the reference restarted from the run's state)", "mm", 1e3),
    ("restart_error_after_hold", "Restart error at the first horizon after a hold", "mm", 1e3),
    ("restart_error_after_release", "Restart error at the first horizon after a release", "mm", 1e3),
    ("restart_error_after_attach", "Restart error at the first horizon after an attach", "mm", 1e3),
    ("restart_error_events_rel", "Restart error after the events / the reference's own motion over the first horizon", "1", 1.0),
    ("restart_motion_events", "The reference's own motion over the first horizon after the events (scale of the restart error)", "mm", 1e3),
    ("short_error_start", "RMS error against the reference 1/30 s after the start", "mm", 1e3),
    ("short_error_events_inherited", "RMS error against the reference at the events", "mm", 1e3),
    ("short_error_events", "RMS error against the reference 1/30 s after the events", "mm", 1e3),
    ("error_rms", "RMS error of the final positions against the reference", "mm", 1e3),
    ("attach_error_mean", "Attach error (distance from p_o + delta n_o)", "mm", 1e3),
    ("energy_drift_max_rel", "Largest relative energy change from the start (manipulations and damping included)", "1", 1.0),
    ("wall_seconds", "Wall time", "s", 1.0),
    ("cpu_seconds", "CPU time (all the run's threads)", "s", 1.0),
)


# The metrics an attach's fixing gives (docs/analysis.md, Attach error): without a value, a run
# whose attach was never fixed failed it, where a run without an attach has nothing to measure.
ATTACH_FIXED = ("attach_error_mean", "vibration_rms_after_attach_fixed")


def attach_note(row, metric):
    """"k not fixed" for a metric of ATTACH_FIXED of a run with k attaches never fixed
    (metrics.attach_unfixed), else empty."""
    count = plots.number(row.get("attach_unfixed_count"))
    return f"{int(count)} not fixed" if metric in ATTACH_FIXED and count > 0 else ""


def method_name(row, parameters):
    """A run's method: integrator, step and the swept values other than the scene."""
    rest = plots.label(row, parameters, ("integrator.dt", "scene") + plots.INTEGRATOR_DETAIL)
    name = plots.method_label(row) + (" (reference)" if row.get("is_reference") else "")
    return name if rest == plots.scene_name(row) else f"{name}, {rest}"


def unfinished(rows):
    """The runs whose status is not ok, in the table's order."""
    return [r for r in rows if r.get("status") != FINISHED]


def stop_word(statuses):
    """"diverged" when every unfinished run of a cell diverged, else "did not finish"."""
    return "diverged" if set(statuses) == {"diverged"} else "did not finish"


def unfinished_banner(rows, parameters):
    """A paragraph naming how many runs did not finish and, per run, its method, scene, status,
    the simulated time it reached of its duration and its reason; empty when every run did."""
    stopped = unfinished(rows)
    if not stopped:
        return ""
    def reached(r):
        t, end = plots.number(r.get("sim_time")), plots.number(r.get("duration"))
        return "" if math.isnan(t) else f"{t:g} s" + ("" if math.isnan(end) else f" of {end:g} s")
    items = "".join(f"<tr><td>{html.escape(method_name(r, parameters))}</td><td>"
                    f"{html.escape(plots.scene_name(r))}</td><td>{html.escape(str(r.get('status')))}</td>"
                    f"<td>{reached(r)}</td><td>{html.escape(str(r.get('reason') or ''))}</td></tr>"
                    for r in stopped)
    table = ("<table><tr><th>method</th><th>scene</th><th>status</th><th>reached</th>"
             f"<th>reason</th></tr>{items}</table>")
    if len(stopped) > BANNER_ROWS:
        table = f"<details><summary>the {len(stopped)} runs</summary>{table}</details>"
    return (f"<div class='banner'><p><b>{len(stopped)} of {len(rows)} runs did not finish</b> "
            f"({stop_word(r.get('status') for r in stopped)}): they have no metrics (their files "
            "stop where they stopped); the summary counts them in each cell.</p>" + table + "</div>")


def summary_cell(r, metric, scale):
    """One cell of a summary table: the mean in the table's unit, +- the Student-t 95 %
    half-width over the runs with a value (marked with a dagger when the interval reaches below
    0: every summary metric is a magnitude), and, for a method run more than once, their number
    n, "of N" when some of its N runs have none, how many of them did not finish and, for an
    attach's metric, how many finished runs never fixed an attach; without a value, the runs
    that did not finish, those whose attach was not fixed, or a dash: the metric does not apply."""
    count, runs, stopped = r[f"{metric}_n"], r["n"], r["unfinished"]
    word = stop_word(r["statuses"])
    unfixed = r["unfixed"] if metric in ATTACH_FIXED else 0
    if not count:
        if stopped:
            return f"{word} ({stopped} of {runs})"
        return f"not fixed ({unfixed} of {runs})" if unfixed else "&ndash;"
    mean, half = r[f"{metric}_mean"] * scale, r[f"{metric}_ci95"] * scale
    value = f"{mean:.3g}"
    if count > 1:
        value += f" &plusmn; {half:.2g}" + ("&dagger;" if mean - half < 0 else "")
    if runs > 1:
        value += f" (n={count}" + (f" of {runs}" if count < runs else "")
        value += (f"; {stopped} {word}" if stopped else "") + (f"; {unfixed} not fixed" if unfixed else "") + ")"
    elif unfixed:
        value += " (an attach not fixed)"
    return value


def summary_tables(rows, parameters):
    """Method x scene tables of the main metrics (mean over repeats, +- the 95 % half-width when
    a method was run more than once), in their units; empty metrics left out."""
    # The repeats of an ensemble differ only in their seed (docs/experiments.md, "Ensembles"):
    # one method, one row.
    parameters = [p for p in parameters if p != plots.REPEAT_PARAMETER]
    # Only finished runs give values: a diverged run's energy rows stop before it blows up (its
    # drift reads 0 when it diverged before the first), and its other metrics measure nothing.
    frame = pd.DataFrame([{"method": method_name(r, parameters), "scene": plots.scene_name(r),
                           "status": r.get("status"),
                           "unfixed": r.get("status") == FINISHED and plots.number(r.get("attach_unfixed_count")) > 0,
                           **{m: plots.number(r.get(m)) if r.get("status") == FINISHED else math.nan
                              for m, *_ in SUMMARY_METRICS}} for r in rows])
    if frame.empty:
        return ""
    order = list(dict.fromkeys(frame["method"]))
    summary = stats.summarise(frame, ["method", "scene"], [m for m, *_ in SUMMARY_METRICS])
    statuses = frame[frame["status"] != FINISHED].groupby(["method", "scene"])["status"].agg(list)
    summary["statuses"] = [statuses.get((m, s), []) for m, s in zip(summary["method"], summary["scene"])]
    summary["unfinished"] = summary["statuses"].map(len)
    unfixed = frame.groupby(["method", "scene"])["unfixed"].sum()
    summary["unfixed"] = [int(unfixed[(m, s)]) for m, s in zip(summary["method"], summary["scene"])]
    parts = []
    for metric, title, unit, scale in SUMMARY_METRICS:
        if not summary[f"{metric}_n"].any() and not (metric in ATTACH_FIXED and summary["unfixed"].any()):
            continue
        cells = summary.apply(lambda r: summary_cell(r, metric, scale), axis=1)
        table = summary.assign(cell=cells).pivot(index="method", columns="scene", values="cell")
        table = table.reindex([m for m in order if m in table.index]).fillna("&ndash;")
        head = "".join(f"<th>{html.escape(c)}</th>" for c in table.columns)
        body = "".join(f"<tr><th>{html.escape(m)}</th>" + "".join(f"<td>{v}</td>" for v in table.loc[m]) + "</tr>"
                       for m in table.index)
        parts.append(f"<h3>{html.escape(title)} [{unit}]</h3><table class='summary'><tr><th>method</th>"
                     f"{head}</tr>{body}</table>")
    return "".join(parts)


# The summary's opening paragraph: what a cell is.
SUMMARY_NOTE = (
    "<p>Method x scene: the mean over the n runs with a value &plusmn; the half-width of its "
    "Student-t 95 % confidence interval (t<sub>0.975, n-1</sub> s / &radic;n, s the sample standard "
    "deviation of the n values; none for n = 1). &dagger;: the interval reaches below 0, which a "
    "magnitude cannot: its n values are too few or too spread for the mean to be well determined "
    "(a magnitude's spread is skewed, so read the mean and n, not the interval's lower end). "
    "\"diverged (k of N)\": none of the method's runs finished; \"not fixed (k of N)\": the runs finished "
    "but an attach of theirs was never fixed (the run ended before the attached particle was), "
    "so they have no attach error; a dash: the metric "
    "does not apply (no attach in the scene, say) or its event did not happen.</p>")
