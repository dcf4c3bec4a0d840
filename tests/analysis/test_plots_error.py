"""The work-precision figure (drapeanalysis/plots_error.py, docs/figures.md) on synthetic rows:
only a method with several steps labels them, and no step label overlaps another or crosses an
error bar."""
import unittest

import numpy as np

from figure_test import FigureTest  # first: puts analysis/ on the path
from drapeanalysis import plots, style


def work_rows():
    """implicit-euler at two steps whose points lie close together, two methods at one step."""
    rows = []
    for name, dt, evals, error in (("implicit-euler", 0.0333333, 80, 0.0096),
                                   ("implicit-euler", 0.01, 250, 0.0094),
                                   ("leapfrog", 0.0005, 5000, 0.001), ("arkode-erk", 0.0005, 25000, 1.6e-4)):
        rows += [{"id": f"{name}{dt}{seed}", "scene": "scenes/s.json", "integrator": name,
                  "integrator.dt": dt, "perturbation.seed": seed, "rhs_evals": evals,
                  "wall_seconds": evals * 1e-5, "error_rms": error * (1 + 0.1 * seed)}
                 for seed in (1, 2)]
    return rows


class WorkPrecisionTest(FigureTest):
    def test_only_a_method_with_several_steps_labels_them_and_no_labels_overlap(self):
        _, fig = self.drawn(lambda out: plots.work_precision(
            out, work_rows(), ["integrator.dt", "perturbation.seed"]))
        fig.canvas.draw()
        renderer = fig.canvas.get_renderer()
        for ax in fig.axes:
            self.assertEqual(sorted(t.get_text() for t in ax.texts), ["0.01 s", "0.0333 s"])
            first, second = (t.get_window_extent(renderer) for t in ax.texts)
            self.assertFalse(first.overlaps(second), ax.get_xlabel())
        legend = [t.get_text() for t in fig.legends[0].get_texts()]
        self.assertIn("leapfrog, dt=0.0005 s", legend)
        self.assertIn("implicit-euler", legend)
        self.assertEqual(fig.axes[0].get_ylabel(), "RMS final position error [mm]")
        # leapfrog's mean error, 1 mm x (1.1 + 1.2) / 2, in mm.
        leapfrog = [line for line in fig.axes[0].lines if line.get_color() == style.INTEGRATOR_COLORS["leapfrog"]
                    and line.get_marker() == "o"]
        np.testing.assert_allclose(np.asarray(leapfrog[0].get_ydata(), float), [1.15])

    def test_no_step_label_crosses_an_error_bar(self):
        # The 0.01 s point's bar spans 3 to 16 mm beside the 0.0333 s point near the panel's top
        # (the integrator comparison's wall-time panel): every spot next to the 0.0333 s label
        # crosses it or leaves the axes, so the label must go further out.
        # (right-hand sides, error of seed 1, of seed 2): Student-t bars of 8-11 and 3-16 mm.
        spread = {0.0333333: (80, 0.00938, 0.00962), 0.01: (165, 0.00899, 0.01001)}
        rows = [dict(row, rhs_evals=spread[row["integrator.dt"]][0],
                     wall_seconds=spread[row["integrator.dt"]][0] * 1e-5,
                     error_rms=spread[row["integrator.dt"]][row["perturbation.seed"]])
                if row["integrator.dt"] in spread else row for row in work_rows()]
        _, fig = self.drawn(lambda out: plots.work_precision(out, rows, ["integrator.dt", "perturbation.seed"]))
        fig.canvas.draw()
        renderer = fig.canvas.get_renderer()
        for ax in fig.axes:
            bars = [ax.transData.transform(segment) for collection in ax.collections
                    for segment in collection.get_segments() if len(segment) == 2]
            self.assertTrue(bars)
            for text in ax.texts:
                box = text.get_window_extent(renderer)
                for (x0, y0), (x1, y1) in bars:
                    crosses = (box.x0 < max(x0, x1) and box.x1 > min(x0, x1)
                               and box.y0 < max(y0, y1) and box.y1 > min(y0, y1))
                    self.assertFalse(crosses, (ax.get_xlabel(), text.get_text(), box, (x0, y0, x1, y1)))

if __name__ == "__main__":
    unittest.main()
