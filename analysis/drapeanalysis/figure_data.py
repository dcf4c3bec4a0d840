"""What the report's figures plot, before any drawing: series names from a run's swept values,
the points of an ensemble (mean and 95 % interval over its repeats), step ranks, a run's events,
and the unit a length is plotted in (docs/analysis.md, "Figures")."""
import math

from . import runfiles, stats, table_columns

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


# Lengths are plotted in the unit the report's tables show them in (table_columns.UNITS: mm),
# so a figure and the table beside it read alike; metrics.csv keeps m.
def plotted_unit(key, axis_label):
    """(factor, axis label) to plot the metric `key` with: in the unit of its table heading
    (table_columns.UNITS, .SCALES), its label's "[m]" made that unit; anything else as it is."""
    factor = table_columns.shown_value(key, 1.0)
    if factor != 1.0:
        return factor, axis_label.replace("[m]", f"[{table_columns.UNITS[key]}]")
    return 1.0, axis_label
