"""Readers for the files a run and an experiment write (docs/outputs.md, docs/experiments.md)."""
import csv
import json
from pathlib import Path

import numpy as np

TRACE_COLUMNS = ("t", "index", "x", "y", "z", "vx", "vy", "vz", "fixed", "contact", "event")


def read_json(path):
    """The JSON value of a file."""
    with open(path) as f:
        return json.load(f)


def read_table(path):
    """A numeric CSV file as a dict of column name -> float array."""
    with open(path, newline="") as f:
        header = next(csv.reader(f))
    data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    return {name: data[:, k] for k, name in enumerate(header)}


def read_trace(path):
    """trace.csv as frames: times (K,), positions and velocities (K, N, 3), fixed, contact and
    event flags (K, N). Rows are grouped by time in the order the run wrote them."""
    data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
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
