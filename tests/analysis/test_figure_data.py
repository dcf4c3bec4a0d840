"""figure_data.py: the points a figure plots, before any drawing, against hand computations."""
import math
import unittest

from drapeanalysis import figure_data

# t_{0.975, 2} in closed form (test_stats.py): (2p - 1) sqrt(2 / (4 p (1 - p))), p = 0.975.
T_975_2 = 0.95 * math.sqrt(2 / (4 * 0.975 * 0.025))


class WithIntervalsTest(unittest.TestCase):
    def test_an_ensemble_is_one_point_with_its_interval(self):
        # y = 1, 2, 3 at x = 0.5: mean 2, sample std 1, half-width t s / sqrt(3).
        points = [(0.5, 3.0), (0.1, 7.0), (0.5, 1.0), (0.5, 2.0)]
        (x0, m0, h0, n0, all0), (x1, m1, h1, n1, all1) = figure_data.with_intervals(points)
        self.assertEqual((x0, m0, h0, n0, all0), (0.1, 7.0, 0.0, 1, 1))  # one value: no width
        self.assertEqual((x1, m1, n1, all1), (0.5, 2.0, 3, 3))
        self.assertAlmostEqual(h1, T_975_2 / math.sqrt(3), places=12)

    def test_non_finite_values_are_counted_but_not_averaged(self):
        points = [(1.0, 4.0), (1.0, math.nan), (1.0, 6.0), (2.0, math.nan), (2.0, math.inf)]
        [(x, mean, half, n, count)] = figure_data.with_intervals(points)
        self.assertEqual((x, mean, n, count), (1.0, 5.0, 2, 3))
        # two values 4 and 6: std sqrt(2), half-width t_{0.975,1} sqrt(2) / sqrt(2) = tan(0.475 pi)
        self.assertAlmostEqual(half, math.tan(0.475 * math.pi), places=9)
        self.assertEqual(figure_data.intervals_by_name({"gone": [(2.0, math.nan)]}), {})


class SeriesTest(unittest.TestCase):
    def test_repeats_join_and_references_stay_out(self):
        rows = [{"integrator.dt": 0.001, "integrator.name": "leapfrog", "perturbation.seed": s,
                 "vibration": v, "scene": "scenes/a.json"} for s, v in ((1, 1.0), (2, 3.0))]
        rows.append({"integrator.dt": 0.001, "integrator.name": "leapfrog", "vibration": 100.0,
                     "is_reference": True, "scene": "scenes/a.json"})
        rows.append({"integrator.dt": "", "integrator.name": "leapfrog", "vibration": 5.0,
                     "scene": "scenes/a.json"})  # no x: not a point
        out = figure_data.series(rows, ["integrator.name", "integrator.dt", "perturbation.seed"],
                                 "integrator.dt", "vibration")
        self.assertEqual(list(out), ["name=leapfrog"])
        [(x, mean, half, n, count)] = out["name=leapfrog"]
        self.assertEqual((x, mean, n, count), (0.001, 2.0, 2, 2))
        self.assertAlmostEqual(half, math.tan(0.475 * math.pi), places=9)

    def test_labels_name_the_scene_when_there_are_several(self):
        row = {"scene": "experiments/scenes/combination1_hold_release.json", "cloth.k": 20,
               "duration": 3.0}
        self.assertEqual(figure_data.label(row, ["cloth.k", "duration"]), "k=20")
        self.assertEqual(figure_data.label(row, ["cloth.k"], with_scene=True),
                         "combination1_hold_release, k=20")
        self.assertEqual(figure_data.label(row, []), "combination1_hold_release")


class StepsAndUnitsTest(unittest.TestCase):
    def test_step_ranks_order_the_steps(self):
        rows = [{"integrator.dt": 0.002}, {"dt": 0.0005}, {"integrator.dt": 0.002}, {}]
        self.assertEqual(figure_data.step_ranks(rows), {0.0005: 0, 0.002: 1, math.inf: 2})
        self.assertEqual(figure_data.number("2.5e-3"), 2.5e-3)
        for missing in ("x", "", None):
            self.assertTrue(math.isnan(figure_data.number(missing)), missing)

    def test_lengths_are_plotted_in_millimetres(self):
        self.assertEqual(figure_data.plotted_unit("attach_error_mean", "attach error [m]"),
                         (1e3, "attach error [mm]"))
        self.assertEqual(figure_data.plotted_unit("wall_seconds", "wall time [s]"),
                         (1.0, "wall time [s]"))


if __name__ == "__main__":
    unittest.main()
