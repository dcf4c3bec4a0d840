"""An experiment's results.json (docs/experiments.md, "The table") read for a report: its fields
checked, every number finite, its runs' files there, and its plan the one experiment.json holds
(a stopped `drapelab experiment` left the last invocation's table beside another plan)."""
import math
from pathlib import Path

import pandas as pd

from .figure_catalogue import KNOWN_METRICS
from .runfiles import missing_run_files, read_json
from .values import JSON_TYPES, RESULT_STATUSES, check_status, json_type, shown

# The fields of results.json the analysis reads (docs/experiments.md, "The table"): their JSON
# type and, for a list, its items' type. Other fields are let be: rows carry any swept key.
RESULTS_FIELDS = {"name": (str, None), "question": (str, None), "metrics": (list, str),
                  "parameters": (list, str), "plan_size": (int, None), "columns": (list, str),
                  "runs": (list, dict)}


# The numbers of a results row (experiments/sweep/results_table.cpp): a number or null. A
# string there ("nan", edited in) went into the tables as a blank without a word.
NUMERIC_COLUMNS = ("dt", "steps", "rhs_evals", "wall_seconds", "cpu_seconds", "sim_time", "duration",
                   "particles", "springs", "object_particles", "energy_initial", "energy_final",
                   "energy_drift_max_abs", "energy_drift_max_rel", "energy_drift_final_rel",
                   "energy_rise_max_rel", "hold_count", "release_count", "map_count", "ignored_count",
                   "attach_count", "attach_error_mean", "attach_error_max", "stable_value",
                   "unstable_value", "probes")


def non_finite(value, where=""):
    """The place (`runs[0].wall_seconds`) of the first non-finite number in a JSON value, or
    None. drapelab writes null for a value it has not, never nan or inf: either is damage, and
    the report blanked it without a word."""
    if isinstance(value, float) and not math.isfinite(value):
        return where
    items = (value.items() if isinstance(value, dict) else
             ((f"[{k}]", v) for k, v in enumerate(value)) if isinstance(value, list) else ())
    for key, item in items:
        found = non_finite(item, f"{where}.{key}" if isinstance(value, dict) and where
                           else f"{where}{key}")
        if found is not None:
            return found
    return None


def check_results(doc, path):
    """A ValueError naming results.json and the field when the document lacks a field the report
    reads or holds the wrong type there, names an unknown metric or lists more runs than its
    plan_size, when a run's id is empty, repeated or would name a file outside the report's
    folder (RUN_ID.mp4, view/RUN_ID.html), or its status is not one merge writes."""
    if not isinstance(doc, dict):
        raise ValueError(f"{path}: expected a JSON object, got {json_type(doc)}")
    for key, (kind, item) in RESULTS_FIELDS.items():
        if key not in doc:
            raise ValueError(f"{path}: {key}: missing")
        value = doc[key]
        wrong = next((v for v in value if not isinstance(v, item)), None) if isinstance(value, list) and item else None
        if not isinstance(value, kind) or isinstance(value, bool) or wrong is not None:
            what = JSON_TYPES[kind] + (f" of {JSON_TYPES[item].split(' ', 1)[1]}s" if item else "")
            raise ValueError(f"{path}: {key}: expected {what}, got {shown(value if wrong is None else wrong)}")
    for k, name in enumerate(doc["metrics"]):
        if name not in KNOWN_METRICS:
            raise ValueError(f"{path}: metrics[{k}]: unknown metric {shown(name)} (known: "
                             f"{', '.join(sorted(KNOWN_METRICS))})")
    seen = set()
    for k, run in enumerate(doc["runs"]):
        for key in ("id", "run_dir"):
            if not isinstance(run.get(key), str) or not run[key]:
                raise ValueError(f"{path}: runs[{k}].{key}: expected a non-empty string, got {shown(run.get(key))}")
        if "/" in run["id"] or run["id"] in (".", ".."):
            raise ValueError(f"{path}: runs[{k}].id: {run['id']!r} is not a file name (it names the run's "
                             "animation and viewer page)")
        if run["id"] in seen:
            raise ValueError(f"{path}: runs[{k}].id: {run['id']!r} repeats an earlier run's id")
        seen.add(run["id"])
        check_status(run.get("status"), RESULT_STATUSES, path, f"runs[{k}].status")
        for key in NUMERIC_COLUMNS:
            value = run.get(key)
            if value is not None and (isinstance(value, bool) or not isinstance(value, (int, float))):
                raise ValueError(f"{path}: runs[{k}].{key}: expected a number or null, got {shown(value)}")
    place = non_finite(doc)
    if place is not None:
        raise ValueError(f"{path}: {place}: not a finite number (drapelab writes null, never nan or inf)")
    # merge writes the plan's size and the runs that finished, never more runs than planned.
    if doc["plan_size"] < len(doc["runs"]):
        raise ValueError(f"{path}: plan_size: {doc['plan_size']}, but runs lists {len(doc['runs'])} "
                         "runs (merge writes at most the plan's runs)")


def load_experiment(directory):
    """The results document (results.json) of an experiment folder, as a dict, checked
    (check_results)."""
    path = Path(directory) / "results.json"
    doc = read_json(path)
    check_results(doc, path)
    return doc


def load_complete_experiment(directory):
    """results.json of an experiment folder whose finished runs have all their files; a
    ValueError naming the folder or the missing files otherwise: a report of runs whose files
    are gone would show them as if they had run."""
    directory = Path(directory)
    if not directory.is_dir():
        raise ValueError(f"{directory}: {'not a folder' if directory.exists() else 'no such folder'}")
    if not (directory / "results.json").exists():
        kind = "a run's folder, not an experiment's: " if (directory / "summary.json").exists() else ""
        raise ValueError(f"{directory}: {kind}no results.json (run `drapelab experiment` or `drapelab merge` first)")
    results = load_experiment(directory)
    check_plan(directory, results)
    if not results.get("runs"):
        raise ValueError(f"{directory / 'results.json'}: no runs (an experiment with an empty plan, or a "
                         "merge before any shard finished)")
    if len(results["runs"]) < results["plan_size"]:
        raise ValueError(f"{directory / 'results.json'}: {len(results['runs'])} of {results['plan_size']} "
                         "planned runs have a result (a merge that named missing runs, or an experiment "
                         "that was stopped): run the rest (`drapelab experiment` resumes, shards run "
                         "again) and `drapelab merge`, then report")
    missing = [str(path) for row in results["runs"] for path in missing_run_files(directory, row)]
    if missing:
        listed = ", ".join(missing[:5]) + (f" and {len(missing) - 5} more" if len(missing) > 5 else "")
        raise ValueError(f"{directory}: runs listed in results.json lack their files: {listed} "
                         "(remove such a run's result.json and rerun `drapelab experiment` to redo it)")
    return results


def results_table(directory):
    """The runs of an experiment's results.json as a DataFrame, one row per run, columns in the
    document's order."""
    doc = load_experiment(directory)
    frame = pd.DataFrame(doc["runs"])
    return frame[[c for c in doc["columns"] if c in frame.columns]
                 + [c for c in frame.columns if c not in doc["columns"]]]


def check_plan(directory, results):
    """A ValueError when results.json is not of the plan experiment.json holds (its plan_size,
    its runs' ids): `drapelab experiment` writes experiment.json first and results.json last,
    so one stopped on a changed plan could leave the last invocation's table, and the report
    would show the old runs as the experiment. A folder without
    experiment.json (a table copied alone) is let be."""
    path = Path(directory) / "experiment.json"
    if not path.exists():
        return
    header = read_json(path)
    plan = header.get("plan") if isinstance(header, dict) else None
    size = header.get("plan_size") if isinstance(header, dict) else None
    if not isinstance(plan, list) or not isinstance(size, int) or isinstance(size, bool):
        raise ValueError(f"{path}: expected plan_size (an integer) and plan (a list): not one drapelab wrote")
    if results["plan_size"] != size:
        stale = f"results.json plans {results['plan_size']} runs, experiment.json {size}"
    else:
        planned = {run.get("id") for run in plan if isinstance(run, dict)}
        stale = next((f"results.json's run {row['id']!r} is not in experiment.json's plan"
                      for row in results["runs"] if row["id"] not in planned), None)
    if stale:
        raise ValueError(f"{directory}: {stale}: the table is of another invocation (one stopped before it "
                         "wrote its own); run `drapelab experiment` again to finish it, then report")

