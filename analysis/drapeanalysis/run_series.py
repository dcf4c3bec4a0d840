"""A run's time series (energy.csv, hands.csv, trace.csv, event_trace/, restart_error.csv) read
against its summary.json: each must reach the run's end (docs/outputs.md, "Every run steps
through one loop").

A file cut short (a full disk, a copy stopped half way) can still end on a whole row, so every
row parses and the times increase: only the run's `sim_time` tells that the file stops early, and
its metrics would describe the start of the run only. A writer's last row may fall short of
`sim_time` by its output interval and a step, no more: rows are written at the first step end at or
after each multiple of the interval, and a diverged or failed run does not write its last step.
event_trace/ ends with the window after the last event instead, and restart_error.csv has the
number of rows the summary counts."""
from pathlib import Path

from . import runfiles
from .values import finite_number, shown

# Each series: its reader, the scene key of its output interval and that key's default
# (docs/scene.md). hands.csv is written on energy.csv's clock (experiments/runner/run_scene.cpp).
SERIES = {
    "energy.csv": (runfiles.read_energy, "output.energy_interval", 0.01),
    "hands.csv": (runfiles.read_hands, "output.energy_interval", 0.01),
    "trace.csv": (runfiles.read_trace, "output.trace_interval", 0.0),
}


def _scene_number(summary, path, key, default):
    return finite_number(runfiles.scene_value(summary, key, default), path, f"scene.{key}")


def _check_reaches(path, last, reach, what, summary, run, interval_key, default, noun="rows"):
    """A ValueError naming `path` when its last time `last` falls short of `reach` (`what`, from
    summary.json) by more than the output interval `interval_key` and the run's longest step."""
    summary_path = Path(run) / "summary.json"
    interval = _scene_number(summary, summary_path, interval_key, default)
    step = finite_number(summary.get("step_max", 0.0), summary_path, "step_max")
    if last < reach - (interval + step + 1e-9 * max(abs(reach), 1.0)):
        raise ValueError(f"{path}: the {noun} end at t = {last:g} s, before {what} = {reach:g} s "
                         f"in summary.json (more than {interval_key} = {interval:g} s and a step "
                         f"of {step:g} s): the file is cut")


def run_end(run, summary):
    """The run's sim_time from its summary.json; a ValueError naming it when there is none."""
    summary_path = Path(run) / "summary.json"
    if "sim_time" not in summary:
        raise ValueError(f"{summary_path}: no sim_time")
    return finite_number(summary["sim_time"], summary_path, "sim_time")


def read_run_series(run, summary, name):
    """The file `name` of SERIES in the run folder `run` as its reader returns it; a ValueError
    naming the file when its rows end before the run's `sim_time` (summary.json) by more than
    its output interval and the run's longest step."""
    reader, interval_key, default = SERIES[name]
    path = Path(run) / name
    rows = reader(path)
    _check_reaches(path, float(rows["t"].iloc[-1]), run_end(run, summary), "the run's sim_time",
                   summary, run, interval_key, default)
    return rows


def read_run_event_trace(run, summary=None):
    """runfiles.read_event_trace of the run (None without event_trace/); a ValueError naming
    t.npy when its frames end before the last window does: `output.event_trace_window` after the
    last event at or before sim_time that changed the state (not an ignored key; or the start), or sim_time when that is earlier. Arrays cut
    alike kept their shapes, and the vibration after the later events read a few frames or none.
    `summary` is read from the run folder when not given."""
    frames = runfiles.read_event_trace(run)
    if frames is None:
        return None
    summary = runfiles.read_summary(run) if summary is None else summary
    end = run_end(run, summary)
    window = _scene_number(summary, Path(run) / "summary.json", "output.event_trace_window", 0.5)
    # An ignored key changes nothing, so it opens no window (event_trace_recorder.cpp).
    starts = [0.0] + [float(e["t"]) for e in summary.get("events", [])
                      if e["t"] <= end and e.get("type") != "ignored"]
    _check_reaches(Path(run) / "event_trace" / "t.npy", float(frames["t"][-1]),
                   min(max(starts) + window, end), "the last event's window end", summary, run,
                   "output.event_trace_interval", 0.0, "frames")
    return frames


def read_run_restart_error(run, summary=None):
    """runfiles.read_restart_error of the run's restart_error.csv; a ValueError naming it when
    it has another number of rows than summary.json's restart_error.rows (a file cut at a row
    boundary lost branches, and the means changed without a word). `summary` is read from the
    run folder when not given."""
    path, summary_path = Path(run) / "restart_error.csv", Path(run) / "summary.json"
    rows = runfiles.read_restart_error(path)
    summary = runfiles.read_summary(run) if summary is None else summary
    section = summary.get("restart_error", {})
    if not isinstance(section, dict):
        raise ValueError(f"{summary_path}: restart_error: expected an object, got {shown(section)}")
    expected = section.get("rows")
    if expected is not None and (not isinstance(expected, int) or isinstance(expected, bool)):
        raise ValueError(f"{summary_path}: restart_error.rows: expected an integer, got {shown(expected)}")
    if expected is not None and len(rows) != expected:
        raise ValueError(f"{path}: {len(rows)} rows, but summary.json's restart_error.rows is "
                         f"{expected}: the file is cut or was changed")
    return rows
