"""The accuracy-against-cost figure (plots_accuracy_cost.py, docs/figures.md) on a synthetic
results table with known numbers: each point at the mean cost and error of its runs with their
95 % Student-t half-widths, the real-time line at x = 1, a diverged setting marked at the cost
its runs reached, and an integrator the style does not know in a colour of its own."""
import math
import tempfile
import unittest
from pathlib import Path
from unittest import mock

import matplotlib.pyplot as plt
import numpy as np

from runfolder import ANALYSIS_DIR  # noqa: F401  (makes drapeanalysis importable)
from drapeanalysis import plots, plots_accuracy_cost, stats, style  # noqa: E402
from drapeanalysis.figure_catalogue import CAPTIONS, KNOWN_METRICS, figure_metrics  # noqa: E402

PARAMETERS = ["integrator.name", "integrator.dt", "perturbation.seed"]
# t_{0.975, 2}: the 95 % half-width of three runs is T2 * std / sqrt(3).
T2 = stats.t_quantile(0.975, 2)


def run(integrator, dt, seed, wall, sim, error=math.nan, later=math.nan, vibration=math.nan,
        status="ok", reference=False):
    return {"id": f"{integrator}-{dt}-{seed}", "scene": "scenes/combination4.json",
            "integrator": integrator, "integrator.name": integrator, "integrator.dt": dt,
            "perturbation.seed": seed, "wall_seconds": wall, "sim_time": sim, "status": status,
            "restart_error_after_hold": error, "restart_error_after_hold_100ms": later,
            "vibration_rms_after_hold": vibration, "is_reference": reference}


ROWS = (
    # leap-frog at 0.1 ms: costs 2, 3, 4 s per simulated second, errors 2, 3, 4 mm.
    [run("leapfrog", 1e-4, s, wall=1.0 + s, sim=1.0, error=1e-3 * (1 + s), later=1e-2 * (1 + s),
         vibration=1e-3) for s in (1, 2, 3)]
    # leap-frog at 0.5 ms diverged in every run, each after 0.25 s and 0.5 s of wall time.
    + [run("leapfrog", 5e-4, s, wall=0.5, sim=0.25, status="diverged") for s in (1, 2, 3)]
    # implicit Euler at 1/30 s: costs 0.1, 0.2, 0.3 over 1.2 s, errors 10, 12, 14 mm.
    + [run("implicit-euler", 1 / 30, s, wall=0.12 * s, sim=1.2, error=8e-3 + 2e-3 * s,
           later=3e-2 + 1e-2 * s, vibration=1e-4) for s in (1, 2, 3)]
    # An integrator the style does not know, one run.
    + [run("xpbd", 1 / 30, 1, wall=0.05, sim=1.0, error=0.05, later=0.06, vibration=5e-4)]
    + [run("leapfrog", 2e-5, 1, wall=20.0, sim=1.0, reference=True)])


class AccuracyCostTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        """The figure drawn once, saved as the report saves it (log ticks, layout) and kept open."""
        cls._tmp = tempfile.TemporaryDirectory()
        kept = []
        with mock.patch.object(style.plt, "close", kept.append):
            cls.stem = plots.accuracy_cost(Path(cls._tmp.name), ROWS, PARAMETERS)
        cls.fig = kept[0]

    @classmethod
    def tearDownClass(cls):
        plt.close("all")
        cls._tmp.cleanup()

    def figure(self):
        self.assertEqual(self.stem, "accuracy_cost")
        return self.fig

    def test_points_are_the_ensemble_means_and_student_t_half_widths(self):
        fig = self.figure()
        first, later = fig.axes[:2]
        half = T2 * 1.0 / math.sqrt(3)  # std 1 of (2, 3, 4) and of (10, 12, 14) / 2
        expected = {  # colour: (x, x half-width, y [mm], y half-width [mm]) in each panel
            style.INTEGRATOR_COLORS["leapfrog"]: ((3.0, half, 3.0, half), (3.0, half, 30.0, 10 * half)),
            style.INTEGRATOR_COLORS["implicit-euler"]: ((0.2, 0.1 * half, 12.0, 2 * half),
                                                        (0.2, 0.1 * half, 50.0, 10 * half)),
        }
        for ax, k in ((first, 0), (later, 1)):
            bars = {bar.lines[0].get_color(): bar for bar in ax.containers}
            for color, values in expected.items():
                x, x_half, y, y_half = values[k]
                line, _, (x_bars, y_bars) = bars[color].lines
                np.testing.assert_allclose(np.asarray(line.get_xdata(), float), [x])
                np.testing.assert_allclose(np.asarray(line.get_ydata(), float), [y])
                (x0, _), (x1, _) = x_bars.get_segments()[0]
                (_, y0), (_, y1) = y_bars.get_segments()[0]
                np.testing.assert_allclose([x0, x1], [x - x_half, x + x_half])
                np.testing.assert_allclose([y0, y1], [y - y_half, y + y_half])
        self.assertEqual(first.get_xscale(), "log")
        self.assertEqual(first.get_yscale(), "log")

    def test_the_real_time_line_is_at_one_and_on_the_axis(self):
        for ax in self.figure().axes[:2]:
            real_time = [line for line in ax.lines if line.get_label() == "real time (x = 1)"]
            self.assertEqual(len(real_time), 1)
            np.testing.assert_allclose(real_time[0].get_xdata(), [1.0, 1.0])
            low, high = ax.get_xlim()
            self.assertTrue(low < 1.0 < high)
            reference = [line for line in ax.lines if line.get_label().startswith("reference")]
            np.testing.assert_allclose(reference[0].get_xdata(), [20.0, 20.0])

    def test_a_diverged_setting_is_marked_at_the_cost_its_runs_reached(self):
        fig = self.figure()
        for ax in fig.axes[:2]:
            self.assertIn("0.0005 s: diverged (3 of 3)", [t.get_text() for t in ax.texts])
            crosses = [line for line in ax.lines if line.get_marker() == style.FAILED_MARK
                       and len(line.get_xdata())]
            self.assertEqual(len(crosses), 1)
            np.testing.assert_allclose(crosses[0].get_xdata(), [0.5 / 0.25])
            self.assertEqual(crosses[0].get_color(), style.INTEGRATOR_COLORS["leapfrog"])

    def test_an_unknown_integrator_gets_a_colour_of_its_own(self):
        fig = self.figure()
        known = {style.INTEGRATOR_COLORS[name] for name in
                 ("leapfrog", "symplectic-euler", "implicit-euler", "arkode-erk", "arkode-dirk", "arkode-imex")}
        xpbd = style.integrator_color({"integrator": "xpbd"})
        self.assertNotIn(xpbd, known)
        self.assertEqual(style.integrator_color({"integrator": "xpbd"}), xpbd)  # stable
        colours = {bar.lines[0].get_color() for bar in fig.axes[0].containers}
        self.assertIn(xpbd, colours)
        self.assertNotIn(style.integrator_marker({"integrator": "xpbd"}), set(style.INTEGRATOR_MARKERS.values())
                         - {style.integrator_marker({"integrator": "xpbd"})})

    def test_declared_order_keeps_the_six_colours_and_gives_the_next(self):
        style.declare_integrators(["leapfrog", "symplectic-euler", "implicit-euler", "arkode-erk",
                                   "arkode-dirk", "arkode-imex", "vbd-declared-test"])
        self.assertEqual(style.INTEGRATOR_COLORS["leapfrog"], "tab:blue")
        self.assertEqual(style.INTEGRATOR_COLORS["arkode-imex"], "tab:brown")
        self.assertIn(style.INTEGRATOR_COLORS["vbd-declared-test"], style.EXTRA_COLORS)

    def test_steps_and_the_settings_of_one_integrator_are_labelled(self):
        rows = ROWS + [run("implicit-euler", 1 / 30, s, wall=0.5, sim=1.2, error=1e-2, vibration=1e-4)
                       | {"integrator.linear_tolerance": 0.1, "id": f"tol-{s}"} for s in (1, 2, 3)]
        kept = []
        with mock.patch.object(style.plt, "close", kept.append):
            plots.accuracy_cost(Path(self._tmp.name), rows, PARAMETERS + ["integrator.linear_tolerance"])
        labels = {t.get_text() for t in kept[0].axes[0].texts}
        self.assertTrue({"0.0001 s", "linear_tolerance=0.1"} <= labels, labels)

    def test_a_solvers_work_per_step_joins_its_points(self):
        # xpbd at 1/30 s with 10 and 20 substeps, vbd with 5 iterations: one line for xpbd
        # labelled by its substeps, the step they share in the legend.
        rows = [run("xpbd", 1 / 30, s, wall=0.1 * k, sim=1.0, error=1e-2 / k, vibration=1e-3)
                | {"integrator.substeps": 10 * k, "id": f"xpbd-{k}-{s}"} for k in (1, 2) for s in (1, 2)]
        rows += [run("vbd", 1 / 30, 1, wall=0.3, sim=1.0, error=2e-2, vibration=1e-3)
                 | {"integrator.iterations": 5}]
        parameters = PARAMETERS + ["integrator.substeps", "integrator.iterations"]
        settings = plots_accuracy_cost.points(rows, parameters, "restart_error_after_hold",
                                              "wall_seconds")["combination4"]
        self.assertEqual(set(settings), {"xpbd", "vbd"})
        self.assertEqual([p["text"] for p in settings["xpbd"]], ["substeps=10", "substeps=20"])
        self.assertEqual(settings["xpbd"][0]["fixed"], "dt=0.0333 s")
        self.assertEqual(settings["vbd"][0]["fixed"], "dt=0.0333 s, iterations=5")
        np.testing.assert_allclose([p["x"] for p in settings["xpbd"]], [0.1, 0.2])
        np.testing.assert_allclose([p["y"] for p in settings["xpbd"]], [10.0, 5.0])
        kept = []
        with mock.patch.object(style.plt, "close", kept.append):
            plots.accuracy_cost(Path(self._tmp.name), rows, parameters)
        self.assertTrue({"substeps=10", "substeps=20"} <= {t.get_text() for t in kept[0].axes[0].texts})

    def test_cpu_time_is_the_cost_where_the_runs_have_it(self):
        # The CPU time is a tenth of the wall time (a shared machine): x follows the CPU time.
        rows = [r | {"cpu_seconds": 0.1 * r["wall_seconds"]} for r in ROWS]
        self.assertEqual(plots_accuracy_cost.cost_column(rows), ("cpu_seconds", "CPU"))
        self.assertEqual(plots_accuracy_cost.cost_column(ROWS), ("wall_seconds", "wall"))
        kept = []
        with mock.patch.object(style.plt, "close", kept.append):
            plots.accuracy_cost(Path(self._tmp.name), rows, PARAMETERS)
        ax = kept[0].axes[0]
        self.assertEqual(ax.get_xlabel(), "CPU seconds per simulated second (real time = 1)")
        bars = {bar.lines[0].get_color(): bar for bar in ax.containers}
        line = bars[style.INTEGRATOR_COLORS["leapfrog"]].lines[0]
        np.testing.assert_allclose(np.asarray(line.get_xdata(), float), [0.3])
        reference = [line for line in ax.lines if line.get_label().startswith("reference")]
        np.testing.assert_allclose(reference[0].get_xdata(), [2.0, 2.0])

    def test_marker_size_grows_with_the_vibration(self):
        low, high = plots_accuracy_cost.SIZE_RANGE
        self.assertAlmostEqual(plots_accuracy_cost.marker_size(1e-4, 1e-4, 1e-3), low)
        self.assertAlmostEqual(plots_accuracy_cost.marker_size(1e-3, 1e-4, 1e-3), high)
        self.assertAlmostEqual(plots_accuracy_cost.marker_size(10 ** -3.5, 1e-4, 1e-3), (low + high) / 2)

    def test_no_error_after_a_hold_no_figure(self):
        rows = [run("leapfrog", 1e-4, 1, wall=1.0, sim=1.0)]
        self.assertIsNone(plots.accuracy_cost(Path(self._tmp.name), rows, PARAMETERS))

    def test_the_report_asks_for_both_metrics_and_has_a_caption(self):
        self.assertEqual(set(figure_metrics("accuracy_cost")), {"restart_error", "vibration"})
        self.assertTrue({"restart_error", "vibration"} <= KNOWN_METRICS)
        self.assertIn("real time", CAPTIONS["accuracy_cost"])
