"""A run's time series (energy.csv, hands.csv, trace.csv) read against its summary.json: each
must reach the run's end (docs/outputs.md, "Every run steps through one loop").

A file cut short (a full disk, a copy stopped half way) can still end on a whole row, so every
row parses and the times increase: only the run's `sim_time` tells that the file stops early, and
its metrics would describe the start of the run only. A writer's last row may fall short of
`sim_time` by its output interval and a step, no more: rows are written at the first step end at or
after each multiple of the interval, and a diverged or failed run does not write its last step."""
from pathlib import Path

from . import runfiles
from .values import finite_number

# Each series: its reader, the scene key of its output interval and that key's default
# (docs/scene.md). hands.csv is written on energy.csv's clock (experiments/run/run_scene.cpp).
SERIES = {
    "energy.csv": (runfiles.read_energy, "output.energy_interval", 0.01),
    "hands.csv": (runfiles.read_hands, "output.energy_interval", 0.01),
    "trace.csv": (runfiles.read_trace, "output.trace_interval", 0.0),
}


def read_run_series(run, summary, name):
    """The file `name` of SERIES in the run folder `run` as its reader returns it; a ValueError
    naming the file when its rows end before the run's `sim_time` (summary.json) by more than
    its output interval and the run's longest step."""
    reader, interval_key, default = SERIES[name]
    path, summary_path = Path(run) / name, Path(run) / "summary.json"
    rows = reader(path)
    if "sim_time" not in summary:
        raise ValueError(f"{summary_path}: no sim_time")
    end = finite_number(summary["sim_time"], summary_path, "sim_time")
    interval = finite_number(runfiles.scene_value(summary, interval_key, default), summary_path,
                             f"scene.{interval_key}")
    step = finite_number(summary.get("step_max", 0.0), summary_path, "step_max")
    slack = interval + step + 1e-9 * max(abs(end), 1.0)
    last = float(rows["t"].iloc[-1])
    if last < end - slack:
        raise ValueError(f"{path}: the rows end at t = {last:g} s, before the run's sim_time = "
                         f"{end:g} s in summary.json (more than {interval_key} = {interval:g} s and "
                         f"a step of {step:g} s): the file is cut")
    return rows
