#!/usr/bin/env python3
"""Regenerates the energy-drift regression baselines from an experiment's results.

Usage:
  build/bin/drapelab experiment tests/regression/energy_drift.json --out /tmp/drift
  /usr/bin/python3 analysis/make_baselines.py /tmp/drift tests/regression/energy_drift_baselines.json

Values come from DIR/results.json; the tolerances of entries already in the baseline file are
kept (they are a reviewed choice), new entries get the defaults below. Review the diff.
"""
import argparse
import json
import sys
from pathlib import Path

# Floats compare with a relative tolerance, counters with a percentage (STYLE.md, Tests).
DEFAULT_TOLERANCES = {
    "energy_drift_max_rel": {"rel_tol": 0.05},
    "energy_drift_final_rel": {"rel_tol": 0.2},
    "steps": {"pct_tol": 0},
    "rhs_evals": {"pct_tol": 0},
}


def entry_key(entry):
    """What identifies a baseline: the scene and its overrides."""
    return entry["scene"], json.dumps(entry["overrides"], sort_keys=True)


def make_entry(row, parameters, old):
    """The baseline of one run: its overrides and each checked value with its tolerance."""
    entry = {"scene": row["scene"], "overrides": {key: row[key] for key in parameters if key in row}}
    previous = old.get(entry_key(entry), {}).get("expect", {})
    entry["expect"] = {}
    for metric, default in DEFAULT_TOLERANCES.items():
        tolerance = {k: v for k, v in previous.get(metric, default).items() if k != "value"}
        entry["expect"][metric] = {"value": row[metric], **tolerance}
    return entry


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("results_dir", type=Path)
    parser.add_argument("baselines", type=Path)
    args = parser.parse_args()
    results = json.loads((args.results_dir / "results.json").read_text())
    failed = [row["id"] for row in results["runs"] if row["status"] != "ok"]
    if failed:
        sys.exit(f"{args.results_dir}: runs not ok, no baselines written: {', '.join(failed)}")
    old = {}
    if args.baselines.exists():
        old = {entry_key(e): e for e in json.loads(args.baselines.read_text())["runs"]}
    doc = {
        "experiment": "energy_drift.json",
        "regenerate": [line.strip() for line in __doc__.split("Usage:\n")[1].split("\n\n")[0].splitlines()],
        "runs": [make_entry(row, results["parameters"], old) for row in results["runs"]],
    }
    args.baselines.write_text(json.dumps(doc, indent=2) + "\n")
    print(f"{args.baselines}: {len(doc['runs'])} baselines")


if __name__ == "__main__":
    main()
