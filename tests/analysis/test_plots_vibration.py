"""The per-run metrics against the step (drapeanalysis/plots_vibration.py, docs/figures.md) on
synthetic rows: a step where every run diverged stays on the axis and says so, an all-zero metric
is not an empty log axis, lengths are in mm, every log axis has two labelled ticks."""
import math
import unittest

import numpy as np

from figure_test import FigureTest, texts  # first: puts analysis/ on the path
from drapeanalysis import plots, plots_vibration, style


def vibration_rows(values, key="vibration_rms_final"):
    """Two leapfrog repeats a step: `values` maps step -> (value, status) of each repeat."""
    return [{"id": f"{dt}-{seed}", "scene": "scenes/s.json", "integrator": "leapfrog",
             "integrator.dt": dt, "perturbation.seed": seed, key: y, "status": status}
            for dt, runs in values.items() for seed, (y, status) in enumerate(runs, 1)]


class StepFigureTest(FigureTest):
    PARAMETERS = ["integrator.dt", "perturbation.seed"]

    def test_a_step_where_every_run_diverged_is_an_x_on_the_axis_saying_so(self):
        rows = vibration_rows({0.001: [(1e-3, "ok"), (3e-3, "ok")],
                               0.004: [(math.nan, "diverged"), (math.nan, "diverged")]})
        stem, fig = self.drawn(lambda out: plots.vibration_vs_dt(out, rows, self.PARAMETERS))
        self.assertEqual(stem, "vibration_vs_dt")
        ax = fig.axes[0]
        self.assertEqual(texts(fig), ["diverged (2 of 2)"])
        crosses = [line for line in ax.lines if line.get_marker() == style.FAILED_MARK
                   and len(line.get_xdata())]
        self.assertEqual([list(line.get_xdata()) for line in crosses], [[0.004]])
        low, high = ax.get_xlim()
        self.assertTrue(low < 0.001 and 0.004 < high)  # the failed step is on the axis
        # The mean of 1 and 3 mm, in mm as the tables give it.
        means = [line for line in ax.lines if line.get_marker() == "o"]
        np.testing.assert_allclose(np.asarray(means[0].get_ydata(), float), [2.0])
        self.assertEqual(ax.get_ylabel(), "vibration RMS, last 0.5 s [mm]")

    def test_a_figure_where_every_run_diverged_is_drawn_and_says_so(self):
        # No positive value for a log axis to stand on: a linear axis, both steps marked (this
        # raised "no positive values" from the tick labelling and failed the whole report).
        rows = vibration_rows({0.002: [(math.nan, "diverged")] * 2,
                               0.004: [(math.nan, "diverged")] * 2})
        stem, fig = self.drawn(lambda out: plots.vibration_vs_dt(out, rows, self.PARAMETERS))
        self.assertEqual(stem, "vibration_vs_dt")
        self.assertEqual(fig.axes[0].get_yscale(), "linear")
        self.assertEqual(sorted(texts(fig))[:2], ["diverged (2 of 2)", "diverged (2 of 2)"])

    def test_a_step_whose_runs_finished_without_a_value_says_no_value(self):
        failed = plots_vibration.failed_steps([(0.001, 1.0), (0.002, math.nan), (0.002, math.nan),
                                               (0.004, math.nan), (0.004, 2.0)],
                                              ["ok", "ok", "ok", "diverged", "ok"])
        self.assertEqual(failed, [(0.002, "no value (2 of 2)")])

    def test_contact_switches_all_zero_are_a_linear_axis_that_says_so(self):
        key = "contact_switch_rate_final"
        rows = vibration_rows({0.001: [(0.0, "ok"), (0.0, "ok")], 0.002: [(0.0, "ok"), (0.0, "ok")]},
                              key)
        _, fig = self.drawn(lambda out: plots.vibration_vs_dt(
            out, rows, self.PARAMETERS, key, "contact switches [1/(particle s)]", "contact_switch_vs_dt"))
        ax = fig.axes[0]
        self.assertEqual(ax.get_yscale(), "linear")
        self.assertIn("no contact switches in any run", texts(fig))
        self.assertEqual(ax.get_ylabel(), "contact switches [1/(particle s)]")  # not a length
        # The axis starts at 0: centred on 0 it would show negative rates.
        fig.canvas.draw()
        self.assertEqual(ax.get_ylim()[0], 0.0)
        low, high = ax.get_ylim()
        self.assertTrue(all(tick >= 0 for tick in ax.get_yticks() if low <= tick <= high))

    def test_every_log_axis_has_two_labelled_ticks(self):
        # Values 3 to 8 mm: no power of ten inside the axis, which drew a single label or none.
        rows = vibration_rows({0.001: [(3e-3, "ok"), (3e-3, "ok")], 0.002: [(8e-3, "ok"), (8e-3, "ok")]})
        _, fig = self.drawn(lambda out: plots.vibration_vs_dt(out, rows, self.PARAMETERS))
        fig.canvas.draw()
        for axis in (fig.axes[0].xaxis, fig.axes[0].yaxis):
            low, high = sorted(axis.get_view_interval())
            labelled = [tick for tick in axis.get_major_ticks()
                        if low <= tick.get_loc() <= high and tick.label1.get_text()]
            self.assertGreaterEqual(len(labelled), 2, axis)

if __name__ == "__main__":
    unittest.main()
