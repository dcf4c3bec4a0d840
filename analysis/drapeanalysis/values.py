"""Checks of the values the readers of runfiles.py take from a run's or an experiment's files,
each a ValueError naming the file and the field, or the row (or frame) and the column, in the
words of drapelab's own refusals (exit status 2 in the report)."""
import json
import math

import numpy as np

# The statuses drapelab writes (docs/outputs.md, docs/experiments.md): a run's summary.json, a
# row of results.json (a run that could not run, or whose process died, has no summary), a
# branch of restart_error.csv.
RUN_STATUSES = ("ok", "diverged", "failed")
RESULT_STATUSES = RUN_STATUSES + ("error", "crashed")
RESTART_STATUSES = ("ok", "reference_diverged", "reference_failed", "diverged", "failed")
# JSON type names, for messages.
JSON_TYPES = {str: "a string", int: "an integer", float: "a number", list: "a list", dict: "an object",
              bool: "true or false", type(None): "null"}


def json_type(value):
    """The JSON name of a value's type, for messages."""
    return JSON_TYPES.get(type(value), type(value).__name__)


def shown(value, limit=60):
    """A JSON value as a message quotes it, cut at `limit` characters."""
    text = json.dumps(value)
    return text if len(text) <= limit else text[:limit] + "..."


def finite_number(value, path, field):
    """value as a float; a ValueError naming the file and the field when it is not a finite
    number (null, a string, true, nan)."""
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise ValueError(f"{path}: {field}: expected a finite number, got {shown(value)}")
    return float(value)


def check_increasing(path, times, where=None):
    """A ValueError naming `path` and where its first time is that is not after the one before
    it (`where(k)` for the k-th time; row k + 1, column t by default): every file a run writes
    grows in time (a repeated time would be a frame twice, a time going back a frame out of
    order; both change the metrics silently)."""
    times = np.asarray(times, float)
    wrong = np.nonzero(~(np.diff(times) > 0))[0]
    if len(wrong):
        k = int(wrong[0]) + 1
        place = where(k) if where else f"row {k + 1}, column t"
        raise ValueError(f"{path}: {place}: t = {times[k]:.17g} is not after the time before it, "
                         f"t = {times[k - 1]:.17g} (times must increase)")


def check_flags(path, values, where):
    """A ValueError naming `path` and where its first value is (`where(k)` for the k-th) that is
    neither 0 nor 1: a flag, read as true or false, whatever else it holds."""
    values = np.asarray(values).ravel()
    wrong = np.nonzero((values != 0) & (values != 1))[0]
    if len(wrong):
        k = int(wrong[0])
        raise ValueError(f"{path}: {where(k)}: {values[k]:g}, expected 0 or 1")


def check_status(value, allowed, path, field):
    """A ValueError naming the file and the field when `value` is not one of the statuses
    `allowed`: an unknown status would be counted as a failure, or as a result, silently."""
    if not isinstance(value, str) or value not in allowed:
        raise ValueError(f"{path}: {field}: expected one of {', '.join(allowed)}, got {shown(value)}")


def check_finite_array(path, array):
    """A ValueError naming the .npy file `path` and the index of its first value that is not a
    finite number (the frame first)."""
    bad = np.argwhere(~np.isfinite(array))
    if len(bad):
        index = tuple(int(i) for i in bad[0])
        raise ValueError(f"{path}: index {list(index)}: not a finite number ({array[index]})")
