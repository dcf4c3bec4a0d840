"""The study's one table (docs/findings.md): per method and setting, its cost per simulated second
on the paper's 20 x 20 cloth and at 64 x 64, whether it keeps up with real time at 64 x 64, its
vibration after the hold, release and attach, its restart error one frame after the hold and its
energy change over the run, each cell the mean +- the 95 % Student-t half-width over an
ensemble's runs that finished, with their number (stats.interval). The cells come from the
metrics.csv that `drapelab report` writes in each experiment's folder and the methods' resolved
keys from each run's summary.json (`integrator_options`, docs/outputs.md).

    python3 -m drapeanalysis.study_table --small out/integrator_comparison \
        --small out/integrator_regimes_field_solvers --large out/accuracy_cost

A setting found in several --small experiments takes the first's runs (of the --scene), so that
a later experiment only adds the settings the first lacks. With --by-scene DIR it prints instead
one table per metric of one experiment, a row per setting and a column per scene (the regimes'
tables of docs/findings/integrator_regimes.md).
"""
import argparse
import math
import re
import sys
from pathlib import Path

import pandas as pd

from . import runfiles, stats
from .figure_data import number, scene_name

FINISHED = "ok"
# A Kinect frame: steps within a microsecond of it are written as one.
FRAME = 1 / 30
# Real time: a CPU second of stepping per simulated second.
REAL_TIME = 1.0
# The table's columns: (heading, cloth, column, scale to the unit); the cloth is "small" (the
# --small experiments, 20 x 20) or "large" (--large, 64 x 64); column None: real_time.
COLUMNS = (("cost 20 x 20 [CPU s/s]", "small", "cost", 1.0),
           ("cost 64 x 64 [CPU s/s]", "large", "cost", 1.0),
           ("real time at 64 x 64", "large", None, None),
           ("vibration after hold [mm]", "small", "vibration_rms_after_hold", 1e3),
           ("after release [mm]", "small", "vibration_rms_after_release", 1e3),
           ("after attach [mm]", "small", "vibration_rms_after_attach", 1e3),
           ("restart error 1 frame after hold, 20 x 20 [mm]", "small", "restart_error_after_hold", 1e3),
           ("same at 64 x 64 [mm]", "large", "restart_error_after_hold", 1e3),
           ("energy change E(end) - E(0) [mJ]", "small", "energy_change", 1e3))
# The tables by scene (--by-scene): (column, title, scale to the unit).
SCENE_METRICS = (("vibration_rms_after_hold", "Vibration after the hold [mm]", 1e3),
                 ("vibration_rms_after_release", "Vibration after the release [mm]", 1e3),
                 ("vibration_rms_after_attach", "Vibration after the attach [mm]", 1e3),
                 ("restart_error_after_hold", "Restart error one frame after the hold [mm]", 1e3),
                 ("restart_error_after_hold_100ms", "Restart error 0.1 s after the hold [mm]", 1e3),
                 ("restart_error_after_release", "Restart error one frame after the release [mm]", 1e3),
                 ("restart_error_after_attach", "Restart error one frame after the attach [mm]", 1e3),
                 ("energy_change", "Energy change E(end) - E(0) [mJ]", 1e3),
                 ("cost", "Cost [CPU s of stepping per simulated s]", 1.0))
# The methods' order in the table: explicit, one-solve implicit, multistep, DIRK, then the
# field's solvers by how far each iterates.
ORDER = ("leapfrog", "symplectic-euler", "arkode-erk", "implicit-euler", "bdf2", "arkode-dirk",
         "arkode-imex", "xpbd", "projective-dynamics", "vbd")


def step_text(dt):
    """A step as the table writes it: "1/30 s" for a Kinect frame, else in ms."""
    return "1/30 s" if abs(dt - FRAME) < 1e-6 else f"{dt * 1e3:g} ms"


def setting(options, is_reference=False):
    """A method and its setting from a run's resolved `integrator_options`: name, step and the
    keys that make its work per step (substeps, iterations, CG tolerance, DIRK table, where
    bdf2's one solve starts)."""
    name, dt = options["name"], float(options["dt"])
    detail = []
    if name == "xpbd":
        detail.append(f"{options['substeps']} substeps" + ("" if options["iterations"] == 1
                                                           else f" x {options['iterations']} sweeps"))
    elif name in ("projective-dynamics", "vbd"):
        detail.append(f"{options['iterations']} iterations")
    elif name == "implicit-euler":
        detail.append("converged" if options.get("solve") == "converged"
                      else f"CG {float(options['linear_tolerance']):g}")
    elif name == "bdf2":
        # A summary without linearise_about is from a build whose one solve started from y_n.
        if options.get("solve") == "converged":
            detail.append("converged")
        else:
            detail.append("from the predictor" if options.get("linearise_about") == "predictor"
                          else "from y_n")
    elif name.startswith("arkode-"):
        detail.append(str(options.get("table", "")).removeprefix("ARKODE_"))
        if options.get("nonlinear_solver"):
            detail.append(str(options["nonlinear_solver"]))
    text = ", ".join([f"{name} {step_text(dt)}"] + detail)
    return f"reference: {text}" if is_reference else text


def order_key(options, is_reference):
    """Sorts the reference last, then by ORDER, step and work per step."""
    name = options["name"]
    rank = ORDER.index(name) if name in ORDER else len(ORDER)
    work = number(options.get("substeps")) if name == "xpbd" else number(options.get("iterations"))
    tolerance = number(options.get("linear_tolerance"))
    return (bool(is_reference), rank, float(options["dt"]),
            0.0 if math.isnan(work) else work, 0.0 if math.isnan(tolerance) else -tolerance)


def read_runs(directory, scene=None):
    """An experiment's runs (its metrics.csv) of `scene` (a file stem; every scene when None),
    with `setting`, `order`, `cost` (CPU seconds of stepping per simulated second) and
    `energy_change` added and `experiment` its name."""
    directory = Path(directory)
    frame = pd.read_csv(directory / "metrics.csv")
    if scene is not None:
        frame = frame[[scene_name(r) == scene for r in frame.to_dict("records")]]
        if frame.empty:
            raise ValueError(f"{directory / 'metrics.csv'}: no run of the scene {scene}")
    is_reference = frame["is_reference"].astype(str).str.lower() == "true"
    options = [runfiles.read_summary(runfiles.run_dir(directory, r))["integrator_options"]
               for r in frame.to_dict("records")]
    frame = frame.assign(
        is_reference=is_reference,
        setting=[setting(o, ref) for o, ref in zip(options, is_reference)],
        order=[order_key(o, ref) for o, ref in zip(options, is_reference)],
        cost=frame["cpu_seconds"] / frame["sim_time"],
        energy_change=frame.get("energy_final", math.nan) - frame.get("energy_initial", math.nan),
        experiment=runfiles.read_json(directory / "experiment.json")["experiment"]["name"])
    return frame


def cell(runs, column, scale):
    """"mean +- half-width (n)" over the finished runs' finite values in the unit of `scale`
    ("mean (1)" for one value); "diverged (k of N)" or "failed (k of N)" when none finished;
    "–" when the metric does not apply (no run has it) or there are no runs."""
    if runs is None or runs.empty or column not in runs:
        return "–"
    done = runs[runs["status"] == FINISHED]
    count, mean, _, half = stats.interval(pd.to_numeric(done[column], errors="coerce") * scale)
    if count == 0:
        stopped = runs[runs["status"] != FINISHED]
        if stopped.empty:
            return "–"
        word = "diverged" if set(stopped["status"]) == {"diverged"} else "failed"
        return f"{word} ({len(stopped)} of {len(runs)})"
    if count == 1:
        return f"{mean:.3g} (1)"
    return f"{mean:.3g} +- {half:.2g} ({count})"


def real_time(runs):
    """Whether the runs keep up with real time: "yes" when the cost's 95 % interval is at or
    below REAL_TIME, "no" above it, "at the line" when it straddles it; "–" without finished runs."""
    if runs is None or runs.empty:
        return "–"
    count, mean, _, half = stats.interval(runs.loc[runs["status"] == FINISHED, "cost"])
    if count == 0:
        return "–"
    half = 0.0 if math.isnan(half) else half
    return "yes" if mean + half <= REAL_TIME else "no" if mean - half > REAL_TIME else "at the line"


def table(small, large):
    """The Markdown table: `small` a list of read_runs frames (the first with a setting wins),
    `large` one. A row per setting in any of them; the last column names the experiments."""
    chosen, rows = {}, {}
    for frame in small:
        for name, runs in frame.groupby("setting"):
            chosen.setdefault(name, runs)
    large_groups = dict(list(large.groupby("setting")))
    for name, runs in list(chosen.items()) + list(large_groups.items()):
        rows.setdefault(name, runs["order"].iloc[0])
    head = ["method and setting"] + [h for h, *_ in COLUMNS] + ["from"]
    lines = []
    for name in sorted(rows, key=rows.get):
        runs = {"small": chosen.get(name), "large": large_groups.get(name)}
        cells = [real_time(runs[cloth]) if column is None else cell(runs[cloth], column, scale)
                 for _, cloth, column, scale in COLUMNS]
        sources = [r["experiment"].iloc[0] for r in runs.values() if r is not None]
        lines.append([name] + cells + [", ".join(sources)])
    return markdown(head, lines)


def scene_heading(stem):
    """A scene's column: "paper-like 1" for combination1_hold_release, "knit 4" for
    combination4_hold_release_attach_knit; other scenes keep their stem."""
    match = re.fullmatch(r"combination(\d)_[a-z_]*?(?:_(knit|woven))?", stem)
    if not match:
        return stem
    return f"{match.group(2) or 'paper-like'} {match.group(1)}"


def scene_tables(runs):
    """One Markdown table per SCENE_METRICS column that some run has: a row per setting, a
    column per scene in the order of the runs; for an experiment of one scene, one table with a
    column per metric instead."""
    scenes = list(dict.fromkeys(scene_name(r) for r in runs.to_dict("records")))
    runs = runs.assign(scene_stem=[scene_name(r) for r in runs.to_dict("records")])
    settings = runs.groupby("setting")["order"].first().sort_values().index
    measured = [m for m in SCENE_METRICS
                if m[0] in runs and pd.to_numeric(runs[m[0]], errors="coerce").notna().any()]
    if len(scenes) == 1:
        return markdown(["method"] + [title for _, title, _ in measured],
                        [[name] + [cell(runs[runs["setting"] == name], column, scale) for column, _, scale in measured]
                         for name in settings])
    parts = []
    for column, title, scale in measured:
        rows = []
        for name in settings:
            mine = runs[runs["setting"] == name]
            rows.append([name] + [cell(mine[mine["scene_stem"] == s], column, scale) for s in scenes])
        parts.append(f"{title}:\n\n" + markdown(["method"] + [scene_heading(s) for s in scenes], rows))
    return "\n\n".join(parts)


def markdown(head, rows):
    """A Markdown table of a heading row and rows of cells."""
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    return "\n".join(lines + ["| " + " | ".join(row) + " |" for row in rows])


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--small", action="append",
                        help="an experiment folder on the 20 x 20 cloth (metrics.csv; repeatable)")
    parser.add_argument("--large", help="the 64 x 64 experiment folder")
    parser.add_argument("--scene", default="combination4_hold_release_attach",
                        help="the scene (file stem) of the --small experiments' runs")
    parser.add_argument("--by-scene", metavar="DIR", help="print DIR's tables by scene instead")
    args = parser.parse_args(argv)
    if not args.by_scene and not (args.small and args.large):
        parser.error("give --small and --large, or --by-scene")
    try:
        if args.by_scene:
            print(scene_tables(read_runs(args.by_scene)))
        else:
            print(table([read_runs(d, args.scene) for d in args.small], read_runs(args.large)))
    except (OSError, ValueError, KeyError) as e:
        print(f"study_table: {e}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
