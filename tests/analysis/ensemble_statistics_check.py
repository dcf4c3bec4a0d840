#!/usr/bin/env python3
"""The two implementations of ensemble statistics agree (docs/analysis.md, Ensemble statistics):
summary.csv, written by `drapelab experiment` in C++ (experiments/sweep/ensemble_summary.cpp),
against drapeanalysis.summarise over the same experiment's results.csv, group by group, for
every metric summary.csv has: n, mean, sample standard deviation and the 95 % half-width.

Usage: ensemble_statistics_check.py DRAPELAB WORK_DIR
"""
import json
import math
import shutil
import subprocess
import sys
from pathlib import Path

import pandas as pd

from drapeanalysis import summarise


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def main():
    drapelab, work = sys.argv[1], Path(sys.argv[2])
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    # A 3 x 3 cloth hanging from one pin, 4 repeats of 2 steps: the seeded perturbation makes
    # the repeats differ.
    (work / "cloth.json").write_text(json.dumps({
        "cloth": {"rows": 3, "cols": 3, "spacing": 0.02, "origin": [0, 1.4, 0], "particle_mass": 0.001,
                  "k_structural": 20},
        "pins": [[0, 0]], "dummy": None, "integrator": {"name": "leapfrog", "dt": 0.001}, "duration": 0.05}))
    (work / "exp.json").write_text(json.dumps({
        "name": "ensemble", "question": "Do both statistics agree?", "scenes": ["cloth.json"],
        "sweep": {"integrator.dt": [0.001, 0.0005]}, "repeats": 4}))
    done = subprocess.run([drapelab, "experiment", str(work / "exp.json"), "--out", str(work / "out"), "-j", "2"],
                          capture_output=True, text=True, timeout=300)
    if done.returncode:
        fail(f"drapelab experiment: exit {done.returncode}\n{done.stderr}")
    cpp = pd.read_csv(work / "out" / "summary.csv")
    results = pd.read_csv(work / "out" / "results.csv")
    keys = list(cpp.columns[:cpp.columns.get_loc("n")])
    metrics = [c.removesuffix("_mean") for c in cpp.columns if c.endswith("_mean")]
    py = summarise(results, keys, metrics).set_index(keys)
    cpp = cpp.set_index(keys)
    if sorted(py.index) != sorted(cpp.index):
        fail(f"groups differ: {sorted(py.index)} against {sorted(cpp.index)}")
    compared = 0
    for group in cpp.index:
        if cpp.loc[group, "n"] != py.loc[group, "n"]:
            fail(f"{group}: n {cpp.loc[group, 'n']} against {py.loc[group, 'n']}")
        for metric in metrics:
            for stat in ("mean", "std", "ci95"):
                a, b = float(cpp.loc[group, f"{metric}_{stat}"]), float(py.loc[group, f"{metric}_{stat}"])
                same = (math.isnan(a) and math.isnan(b)) or math.isclose(a, b, rel_tol=1e-9, abs_tol=1e-300)
                if not same:
                    fail(f"{group} {metric}_{stat}: C++ {a!r}, Python {b!r}")
                compared += not math.isnan(a)
    varied = (cpp["energy_final_std"] > 0).all()
    if not varied:
        fail("the repeats did not differ: nothing was compared")
    print(f"OK: {len(cpp)} groups, {len(metrics)} metrics, {compared} finite statistics agree")
    return 0


if __name__ == "__main__":
    sys.exit(main())
