"""Ensemble statistics (drapeanalysis/stats.py) against tables and hand computations."""
import math
import unittest

import numpy as np
import pandas as pd

import runfolder  # noqa: F401  (puts analysis/ on the path)
import drapeanalysis
from drapeanalysis import stats


class TQuantileTest(unittest.TestCase):
    def test_table_values(self):
        # Two-sided 95 % values from any t table, to their printed 3 decimals; dof 1 and 2 have
        # closed forms: tan(pi (p - 1/2)) and (2p - 1) sqrt(2 / (4 p (1 - p))).
        for dof, value in ((1, 12.706), (2, 4.303), (4, 2.776), (9, 2.262), (29, 2.045), (120, 1.980)):
            self.assertAlmostEqual(drapeanalysis.t_quantile(0.975, dof), value, places=3)
        self.assertAlmostEqual(stats.t_quantile(0.975, 1), math.tan(0.475 * math.pi), places=9)
        self.assertAlmostEqual(stats.t_quantile(0.975, 2), 0.95 * math.sqrt(2 / (4 * 0.975 * 0.025)), places=9)
        self.assertAlmostEqual(stats.t_quantile(0.975, 1e7), 1.959964, places=5)
        self.assertAlmostEqual(stats.t_quantile(0.025, 4), -2.776445, places=6)
        self.assertAlmostEqual(stats.t_quantile(0.5, 3), 0.0, places=9)

    def test_cdf_is_the_inverse(self):
        for dof in (1, 3, 7.5, 50):
            for p in (0.6, 0.9, 0.995):
                self.assertAlmostEqual(stats.t_cdf(stats.t_quantile(p, dof), dof), p, places=10)

    def test_bad_arguments(self):
        with self.assertRaises(ValueError):
            stats.t_quantile(1.0, 3)
        with self.assertRaises(ValueError):
            stats.t_quantile(0.9, 0)


class SummariseTest(unittest.TestCase):
    def test_known_groups(self):
        # Group a: 1, 2, 3, 4, 5: mean 3, sample std sqrt(2.5), ci95 2.776 sqrt(2.5) / sqrt 5.
        # Group b: 10, 14 and a missing value: n 3, 2 values, mean 12, std 2 sqrt 2, ci95
        # 12.706 x 2 sqrt 2 / sqrt 2 = 25.41. Group c: one value, std and ci95 nan.
        df = pd.DataFrame({
            "method": ["a"] * 5 + ["b"] * 3 + ["c"],
            "scene": "s",
            "rms": [1, 2, 3, 4, 5, 10, 14, np.nan, 7],
            "steps": [10, 10, 10, 10, 10, 1, 2, 3, 4],
        })
        out = drapeanalysis.summarise(df, ["method", "scene"], ["rms", "steps"]).set_index("method")
        self.assertEqual(list(out.index), ["a", "b", "c"])
        self.assertEqual(out.loc["a", "n"], 5)
        self.assertAlmostEqual(out.loc["a", "rms_mean"], 3.0)
        self.assertAlmostEqual(out.loc["a", "rms_std"], math.sqrt(2.5))
        self.assertAlmostEqual(out.loc["a", "rms_ci95"], 2.776445 * math.sqrt(2.5) / math.sqrt(5), places=5)
        self.assertEqual(out.loc["a", "steps_std"], 0.0)
        self.assertEqual(out.loc["b", "n"], 3)
        self.assertEqual(out.loc["b", "rms_n"], 2)
        self.assertAlmostEqual(out.loc["b", "rms_mean"], 12.0)
        self.assertAlmostEqual(out.loc["b", "rms_std"], 2 * math.sqrt(2))
        self.assertAlmostEqual(out.loc["b", "rms_ci95"], 12.706205 * 2, places=5)
        self.assertAlmostEqual(out.loc["b", "steps_ci95"], 4.302653 * 1.0 / math.sqrt(3), places=5)
        self.assertEqual(out.loc["c", "rms_mean"], 7.0)
        self.assertTrue(math.isnan(out.loc["c", "rms_std"]))
        self.assertTrue(math.isnan(out.loc["c", "rms_ci95"]))
        self.assertEqual(out.loc["c", "scene"], "s")

    def test_single_group_column(self):
        df = pd.DataFrame({"dt": [0.1, 0.1, 0.2], "e": [1.0, 3.0, 5.0]})
        out = drapeanalysis.summarise(df, ["dt"], ["e"])
        self.assertEqual(list(out.columns), ["dt", "n", "e_n", "e_mean", "e_std", "e_ci95"])
        self.assertEqual(out["e_mean"].tolist(), [2.0, 5.0])


    def test_plotted_points_are_the_mean_and_half_width_of_the_repeats(self):
        from drapeanalysis import plots
        # x = 1: two repeats 2 and 4, mean 3, std sqrt(2), half-width t(0.975, 1) sqrt(2) / sqrt(2);
        # x = 2: one run, no interval (drawn without a bar).
        points = plots.with_intervals([(2.0, 5.0), (1.0, 2.0), (1.0, 4.0)])
        self.assertEqual([(x, y, n, runs) for x, y, _, n, runs in points],
                         [(1.0, 3.0, 2, 2), (2.0, 5.0, 1, 1)])
        self.assertAlmostEqual(points[0][2], 12.706205, places=5)
        self.assertEqual(points[1][2], 0.0)


if __name__ == "__main__":
    unittest.main()
