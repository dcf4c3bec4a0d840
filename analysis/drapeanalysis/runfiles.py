"""Readers for the files a run and an experiment write (docs/outputs.md, docs/experiments.md)."""
import csv
import json
import warnings
from pathlib import Path

import numpy as np

TRACE_COLUMNS = ("t", "index", "x", "y", "z", "vx", "vy", "vz", "fixed", "contact", "event")


def read_json(path):
    """The JSON value of a file."""
    with open(path) as f:
        try:
            return json.load(f)
        except json.JSONDecodeError as e:
            raise ValueError(f"{path}: not valid JSON: {e}") from e


def load_numbers(path, header, columns=()):
    """The rows of a numeric CSV file with the given header as a (rows, columns) array; a clear
    error naming the file when a required column is missing, a cell is not a number or there are
    no rows."""
    missing = [c for c in columns if c not in header]
    if missing:
        raise ValueError(f"{path}: missing column(s) {', '.join(missing)} (has {', '.join(header)})")
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", UserWarning)  # numpy's "empty input file"
            data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    except ValueError as e:
        raise ValueError(f"{path}: {e}") from e
    if data.shape[0] == 0:
        raise ValueError(f"{path}: no rows")
    if data.shape[1] != len(header):
        raise ValueError(f"{path}: {data.shape[1]} values a row, {len(header)} column names")
    return data


def read_header(path):
    """The column names of a CSV file."""
    with open(path, newline="") as f:
        header = next(csv.reader(f), None)
    if not header:
        raise ValueError(f"{path}: empty file")
    return header


def read_table(path, columns=()):
    """A numeric CSV file as a dict of column name -> float array; `columns` must be present."""
    header = read_header(path)
    data = load_numbers(path, header, columns)
    return {name: data[:, k] for k, name in enumerate(header)}


def read_trace(path):
    """trace.csv as frames: times (K,), positions and velocities (K, N, 3), fixed, contact and
    event flags (K, N). Rows are grouped by time in the order the run wrote them."""
    header = read_header(path)
    if tuple(header) != TRACE_COLUMNS:
        raise ValueError(f"{path}: columns {','.join(header)}, expected {','.join(TRACE_COLUMNS)}")
    data = load_numbers(path, header)
    n = int(data[:, 1].max()) + 1
    if len(data) % n:
        raise ValueError(f"{path}: {len(data)} rows is not a whole number of {n}-particle frames")
    frames = data.reshape(-1, n, len(TRACE_COLUMNS))
    return {
        "t": frames[:, 0, 0],
        "x": frames[:, :, 2:5],
        "v": frames[:, :, 5:8],
        "fixed": frames[:, :, 8].astype(bool),
        "contact": frames[:, :, 9].astype(int),
        "event": frames[:, 0, 10].astype(bool),
    }


def load_experiment(directory):
    """The results table (results.json) of an experiment folder."""
    return read_json(Path(directory) / "results.json")


def run_dir(directory, row):
    """The folder of one run of an experiment."""
    return Path(directory) / row["run_dir"]


def scene_value(summary, path, default):
    """A value of the scene as run (summary.json `scene`), or the documented default."""
    node = summary.get("scene", {})
    for key in path.split("."):
        if not isinstance(node, dict) or key not in node:
            return default
        node = node[key]
    return node
