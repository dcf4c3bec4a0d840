"""The report's figures: what each shows (its caption) and which of an experiment's `metrics`
(docs/experiments.md) asks for it."""

CAPTIONS = {
    "energy_vs_time": "Relative energy change |E(t) - E(0)| / |E(0)| from the start against time, one "
                      "panel per integrator (colour: scene, line style: step). It includes the work of "
                      "the manipulations and the damping, so it is not an error: driven, damped scenes "
                      "change their energy. A run that did not finish ends in an x, its legend entry "
                      "saying when it stopped.",
    "work_precision": "RMS error against the reference (the restart error at the first horizon after the events, the reference "
                      "restarted from the run's state, where the runs measured the restart error; else "
                      "of the final positions), against right-hand-side evaluations and wall time; "
                      "mean over the repeats, bars their 95 % interval.",
    "restart_error_vs_horizon": "Restart error against the horizon: the reference restarted from "
                                "each run's state after each of its events, RMS distance between "
                                "them a horizon later (mean over the runs of each run's mean over "
                                "its events; bars: 95 % interval over the runs).",
    "energy_by_scene": "Total energy E(t) - E(0), one block of panels per scene and one panel per "
                       "integrator (its steps by line style), the reference run dashed black in each; "
                       "dotted lines: the manipulations of one run (the reference's, else the first "
                       "run's: other runs reach them at other times, or not at all), labelled in the "
                       "block's first panel. Driven, damped scenes do not conserve energy: the methods "
                       "are compared with each other. A run that did not finish ends in an x.",
    "attach_error_vs_iterations": "Attach error |x - (p_o + delta n_o)| against "
                                  "manipulation.attach_iterations (paper Figure 5); \"n of N\" beside "
                                  "a point from only n of its N repeats.",
    "attach_error_vs_solver_work": "The same attach error for the field's solvers at one step, "
                                   "against their work per step, the paper's \"calculation time\" "
                                   "read literally: xpbd's substeps, projective dynamics' and vbd's "
                                   "iterations.",
    "attach_error_vs_time": "The same attach error against the simulated time the attached "
                            "particle was left to settle (attach_iterations x dt).",
    "vibration_vs_dt": "Vibration: RMS motion of the free cloth particles above the run's cutoff "
                       "(between its swing and stretch frequencies, docs/analysis.md) over the last "
                       "0.5 s of the run, against the step size; one panel per scene (and collision "
                       "model), one line per integrator and the other swept values; dashed black: "
                       "the reference run. A point is the mean of a method's runs at that step with "
                       "a value (bars: 95 % interval over repeats); \"n of N\" beside it when only n of "
                       "its N runs have one (the others diverged); an x on a panel's floor, "
                       "\"diverged (N of N)\": a step where none of a method's runs has a value. "
                       "Lengths in mm, as in the tables.",
    "vibration_events_vs_dt": "The same, largest over the windows after each manipulation.",
    "contact_switch_vs_dt": "Changes of a particle's nearest object particle in contact per free "
                            "particle and second, last 0.5 s, against the step size (a linear axis "
                            "when a value is 0).",
    "stable_dt": "Largest stable step found by bisection.",
    "accuracy_cost": "Accuracy against cost: the restart error after the hold (the reference restarted "
                     "from the run's state at its hold, RMS distance a horizon later: the first "
                     "horizon, and the largest in the second panel) against CPU seconds per "
                     "simulated second (the stepping's CPU time over the simulated time, wall time "
                     "for runs without it; real time = 1, dash-dotted; the reference's cost "
                     "dashed), one point per method and setting: the mean over its runs, bars the "
                     "95 % Student-t interval of both; the marker's size the vibration after the "
                     "hold; a setting's steps, substeps or iterations joined and labelled; an x on "
                     "the floor, \"diverged (k of N)\": a setting none of whose runs has an error, "
                     "at the cost its runs reached.",
}


# Appended to the captions of the figures whose bars stand on a log axis (style.log_errorbar),
# and of those among them whose series share x values (steps, horizons) and are dodged.
_ARROW = " An arrow at a bar's foot: its 95 % interval reaches 0, which a log axis cannot show"
CAPTIONS["work_precision"] += _ARROW + "."
CAPTIONS["accuracy_cost"] += _ARROW + "."
for _name in ("restart_error_vs_horizon", "attach_error_vs_iterations", "attach_error_vs_solver_work",
              "attach_error_vs_time", "vibration_vs_dt", "contact_switch_vs_dt"):
    CAPTIONS[_name] += _ARROW + "; series at the same x are drawn slightly apart."


# The experiment's `metrics` (docs/experiments.md) each figure belongs to (several: it needs all).
FIGURE_METRIC = {
    "energy_vs_time": "energy_drift", "energy_by_scene": "energy_drift",
    "work_precision": "work_precision", "attach_error_vs_iterations": "attach_error",
    "attach_error_vs_solver_work": "attach_error", "attach_error_vs_time": "attach_error",
    "vibration_vs_dt": "vibration",
    "vibration_events_vs_dt": "vibration", "contact_switch_vs_dt": "vibration",
    "stable_dt": "stable_dt", "restart_error_vs_horizon": "restart_error",
    "accuracy_cost": ("restart_error", "vibration"),
}


def figure_metrics(name):
    """The metrics the figure `name` needs, all of which the experiment must ask for."""
    value = FIGURE_METRIC[name]
    return (value,) if isinstance(value, str) else value


# Every name an experiment's `metrics` may hold: drapelab's known_metrics()
# (experiments/sweep/experiment.cpp), which refuses any other; mapping_error has a column and no
# figure, snapshots figures of their own.
KNOWN_METRICS = frozenset(m for name in FIGURE_METRIC for m in figure_metrics(name)) | {"mapping_error", "snapshots"}
