"""Readers for the files a run and an experiment write (docs/outputs.md, docs/experiments.md):
CSV files as pandas DataFrames (one column per CSV column), JSON files as dicts. Every reader
names the file in its error when it is not a regular file (fileio.open_input), a column is
missing, a cell is not a finite number or there are no rows, and the row and the column when
times do not increase, a flag is not 0 or 1 or a status is not one drapelab writes.

A run never writes a non-finite number: the loop checks a step for divergence (a non-finite or
runaway state) before any writer sees it (experiments/run/simulation.cpp, take_step), so a
diverged run's files end with its last finite step, and inf, like nan, is damage."""
import json
import math
import os
from pathlib import Path

import numpy as np
import pandas as pd

from .fileio import input_problem, open_input
from .values import (RESTART_STATUSES, RUN_STATUSES, check_finite_array, check_flags, check_increasing,
                     check_status, finite_number, json_type, shown)

TRACE_COLUMNS = ("t", "index", "x", "y", "z", "vx", "vy", "vz", "fixed", "contact", "event")
STATE_COLUMNS = ("index", "row", "col", "x", "y", "z", "vx", "vy", "vz", "fixed")
HANDS_COLUMNS = ("t", "hand", "available", "x", "y", "z")
EVENT_TRACE_TYPES = {"t": np.float64, "x": np.float32, "v": np.float32, "fixed": np.uint8, "contact": np.int32}


def read_json(path):
    """The JSON value of a file."""
    with open_input(path) as f:
        try:
            return json.load(f)
        except (json.JSONDecodeError, UnicodeDecodeError) as e:
            raise ValueError(f"{path}: not valid JSON: {e}") from e


def read_csv(path, columns=(), text_columns=(), nan_columns=()):
    """A CSV file as a DataFrame; `columns` must be present, and every column but `text_columns`
    must hold finite numbers (`nan_columns` may also hold nan: a quantity not measured). Every line a
    run writes ends in a newline: a file that does not was cut, and its last number may be cut
    short yet still parse."""
    with open_input(path, "rb") as f:
        if f.seek(0, os.SEEK_END) and f.seek(-1, os.SEEK_END) >= 0 and f.read(1) != b"\n":
            raise ValueError(f"{path}: the last line is cut (the file does not end in a newline)")
        f.seek(0)
        try:
            frame = pd.read_csv(f, dtype={c: str for c in text_columns})
        except pd.errors.EmptyDataError as e:
            raise ValueError(f"{path}: empty file") from e
        except (pd.errors.ParserError, UnicodeDecodeError) as e:
            raise ValueError(f"{path}: {e}") from e
    missing = [c for c in columns if c not in frame.columns]
    if missing:
        raise ValueError(f"{path}: missing column(s) {', '.join(missing)} "
                         f"(has {', '.join(map(str, frame.columns))})")
    if frame.empty:
        raise ValueError(f"{path}: no rows")
    for name in frame.columns:
        if name in text_columns:
            continue
        numbers = pd.to_numeric(frame[name], errors="coerce")
        # to_numeric keeps inf (and 1e999): a number, but not one a run writes.
        bad = (numbers.isna() & frame[name].notna()) | np.isinf(numbers)
        if name not in nan_columns:
            bad |= frame[name].isna()
        if bad.any():
            row = int(np.argmax(bad.to_numpy()))
            raise ValueError(f"{path}: row {row + 1}, column {name}: not a finite number "
                             f"({frame[name].iloc[row]!r})")
        frame[name] = numbers.astype(float)
    return frame


def read_restart_error(path):
    """A run's restart_error.csv (docs/outputs.md): the measured columns are nan where a branch
    failed or the run ended before its horizon; a horizon is positive and a status one of
    RESTART_STATUSES."""
    measured = ("error_rms", "error_max", "reference_motion_rms")
    rows = read_csv(path, ("t", "horizon") + measured, ("events", "status"), measured)
    for k, (status, horizon) in enumerate(zip(rows["status"], rows["horizon"])):
        check_status(status, RESTART_STATUSES, path, f"row {k + 1}, column status")
        if not horizon > 0:
            raise ValueError(f"{path}: row {k + 1}, column horizon: {horizon:g}, expected a positive time")
        # nan only where the branch did not reach its horizon: an ok branch measured all three.
        for name in measured:
            if status == "ok" and not np.isfinite(rows[name].iloc[k]):
                raise ValueError(f"{path}: row {k + 1}, column {name}: not a finite number in a branch "
                                 f"whose status is ok")
    return rows


def read_table(path, columns=()):
    """A numeric CSV file (energy.csv, state.csv, dummy.csv) as a DataFrame of floats."""
    return read_csv(path, columns)


def read_energy(path):
    """energy.csv: t, kinetic, spring, gravity, collision, total; t increasing."""
    energy = read_csv(path, ("t", "total"))
    check_increasing(path, energy["t"])
    return energy


def read_dummy(path):
    """dummy.csv: index, section, point, x, y, z, nx, ny, nz (the drawings need the sections)."""
    return read_csv(path, ("section", "point", "x", "y", "z"))


def read_state(path):
    """state.csv: index, row, col, x, y, z, vx, vy, vz, fixed."""
    return read_csv(path, ("x", "y", "z"))


def read_hands(path):
    """hands.csv: t, hand (left, right), available, x, y, z, candidate, distance, held."""
    return read_csv(path, HANDS_COLUMNS, text_columns=("hand",))


def read_trace(path):
    """trace.csv as a DataFrame, one row per particle and trace time, in the order written:
    each frame every particle in index order at one time, the frames' times increasing, the
    fixed and event flags 0 or 1."""
    frame = read_csv(path)
    if tuple(frame.columns) != TRACE_COLUMNS:
        raise ValueError(f"{path}: columns {','.join(frame.columns)}, expected {','.join(TRACE_COLUMNS)}")
    particles = int(frame["index"].max()) + 1
    if len(frame) % particles:
        raise ValueError(f"{path}: {len(frame)} rows is not a whole number of {particles}-particle frames")
    index, t = frame["index"].to_numpy(), frame["t"].to_numpy()
    first = np.repeat(np.arange(0, len(frame), particles), particles)
    wrong = np.nonzero((index != np.arange(len(frame)) - first) | (t != t[first]))[0]
    if len(wrong):
        r = int(wrong[0])
        raise ValueError(f"{path}: row {r + 1}: particle {index[r]:g} at t = {t[r]:.17g}, expected particle "
                         f"{r - first[r]} of the frame at t = {t[first[r]]:.17g} (a frame lists every "
                         "particle in order at one time)")
    check_increasing(path, t[::particles], lambda k: f"row {k * particles + 1}, column t")
    for name in ("fixed", "event"):
        check_flags(path, frame[name], lambda k: f"row {k + 1}, column {name}")
    return frame


def trace_frames(trace):
    """A trace DataFrame as frames: times (K,), positions and velocities (K, N, 3), fixed and
    contact (K, N), event flags (K,). Rows are grouped by time in the order the run wrote them."""
    data = trace[list(TRACE_COLUMNS)].to_numpy(dtype=float)
    n = int(data[:, 1].max()) + 1
    frames = data.reshape(-1, n, len(TRACE_COLUMNS))
    return {
        "t": frames[:, 0, 0],
        "x": frames[:, :, 2:5],
        "v": frames[:, :, 5:8],
        "fixed": frames[:, :, 8].astype(bool),
        "contact": frames[:, :, 9].astype(int),
        "event": frames[:, 0, 10].astype(bool),
    }


def read_event_trace(run):
    """A run's event_trace/ folder (docs/outputs.md) as frames like trace_frames: times (K,),
    positions and velocities (K, N, 3), fixed and contact (K, N), event flags (K,) true at the
    first frame of each window; None when the run wrote none."""
    folder = Path(run) / "event_trace"
    if not folder.is_dir():
        return None
    arrays = {}
    for name in EVENT_TRACE_TYPES:
        path = folder / f"{name}.npy"
        with open_input(path, "rb") as f:
            try:
                arrays[name] = np.load(f)
            except (OSError, ValueError) as e:
                raise ValueError(f"{path}: {e}") from e
    frames = len(arrays["t"])
    for name in ("x", "v", "fixed", "contact"):
        if len(arrays[name]) != frames:
            raise ValueError(f"{folder / (name + '.npy')}: {len(arrays[name])} frames, t.npy has {frames}")
    for name, array in arrays.items():
        # The types the run writes (docs/outputs.md): times in integer milliseconds, say, would
        # be read as seconds.
        if array.dtype != EVENT_TRACE_TYPES[name]:
            raise ValueError(f"{folder / (name + '.npy')}: {array.dtype} values, expected "
                             f"{np.dtype(EVENT_TRACE_TYPES[name])}")
        check_finite_array(folder / f"{name}.npy", array)
    check_increasing(folder / "t.npy", arrays["t"], lambda k: f"index [{k}]")
    fixed = arrays["fixed"]
    check_flags(folder / "fixed.npy", fixed, lambda k: f"index {list(map(int, np.unravel_index(k, fixed.shape)))}")
    t = arrays["t"].astype(float)
    step = np.diff(t)
    # A window starts where the spacing is not the interval (the median spacing).
    starts = np.ones(frames, dtype=bool)
    if frames > 1:
        starts[1:] = ~np.isclose(step, np.median(step), rtol=1e-6, atol=0)
    return {"t": t, "x": arrays["x"].astype(float), "v": arrays["v"].astype(float),
            "fixed": arrays["fixed"].astype(bool), "contact": arrays["contact"].astype(int),
            "event": starts}


def positions(frame):
    """The x, y, z columns of a state, dummy or trace DataFrame as an (N, 3) array."""
    return frame[["x", "y", "z"]].to_numpy(dtype=float)


def read_summary(run):
    """A run's summary.json as a dict; a ValueError naming the file and the field when it is not
    an object, its status is not one a run writes, or its events (optional) are not a list of
    objects each with a type (a string) and a time `t` (a finite number), which every event of
    docs/outputs.md has."""
    path = Path(run) / "summary.json"
    doc = read_json(path)
    if not isinstance(doc, dict):
        raise ValueError(f"{path}: expected a JSON object, got {json_type(doc)}")
    check_status(doc.get("status"), RUN_STATUSES, path, "status")
    events = doc.get("events", [])
    if not isinstance(events, list):
        raise ValueError(f"{path}: events: expected a list, got {json_type(events)}")
    for k, event in enumerate(events):
        if not isinstance(event, dict):
            raise ValueError(f"{path}: events[{k}]: expected an object, got {json_type(event)}")
        if not isinstance(event.get("type"), str):
            raise ValueError(f"{path}: events[{k}].type: expected a string, got {shown(event.get('type'))}")
        finite_number(event.get("t"), path, f"events[{k}].t")
    return doc


def run_dir(directory, row):
    """The folder of one run of an experiment (row: a results row, dict or pandas Series)."""
    return Path(directory) / row["run_dir"]


def optional_run_files(run, summary):
    """The files a finished run writes only under some settings that its summary.json says it
    wrote (docs/outputs.md): state.csv when it ended ok, dummy.csv with object particles,
    hands.csv with `input`, trace.csv and event_trace/ with their intervals, restart_error.csv
    with `restart_error`. Without one a report or a page would drop what it shows silently."""
    path = Path(run) / "summary.json"

    def positive(value, field):
        return finite_number(value, path, field) > 0

    names = ["state.csv"] if summary.get("status") == "ok" else []
    if positive(summary.get("object_particles", 0), "object_particles"):
        names.append("dummy.csv")
    if scene_value(summary, "input", None) is not None:
        names.append("hands.csv")
    if positive(scene_value(summary, "output.trace_interval", 0), "scene.output.trace_interval"):
        names.append("trace.csv")
    if positive(scene_value(summary, "output.event_trace_interval", 0),
                "scene.output.event_trace_interval"):
        names += [f"event_trace/{name}.npy" for name in EVENT_TRACE_TYPES]
    if "restart_error" in summary:
        names.append("restart_error.csv")
    return names


def missing_files(paths):
    """The `paths` not there; a ValueError naming one there that is not a regular file (a folder,
    a named pipe): it is not missing, it is wrong."""
    missing = []
    for path in paths:
        problem = input_problem(path)
        if problem == "no such file":
            missing.append(path)
        elif problem:
            raise ValueError(f"{path}: {problem}")
    return missing


def missing_run_files(directory, row):
    """The files a run of the results table must have and has not: result.json, then
    summary.json, energy.csv and the files the summary says the run wrote (optional_run_files; a
    bisection: bisect.json); none for a run that could not run or crashed, which has no files to
    report on. A file there that is not a regular file is a ValueError naming it."""
    if row.get("status") in ("error", "crashed"):
        return []
    run = run_dir(directory, row)
    bisection = bool(row.get("bisect_parameter"))
    names = ("bisect.json",) if bisection else ("summary.json", "energy.csv")
    missing = missing_files([run / name for name in ("result.json",) + names])
    if bisection or run / "summary.json" in missing:
        return missing
    return missing + missing_files([run / n for n in optional_run_files(run, read_summary(run))])


def scene_value(summary, path, default):
    """A value of the scene as run (summary.json `scene`), or the documented default."""
    node = summary.get("scene", {})
    for key in path.split("."):
        if not isinstance(node, dict) or key not in node:
            return default
        node = node[key]
    return node
