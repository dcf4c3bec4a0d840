"""The report's figures (analysis/drapeanalysis/plots*.py) on synthetic runs (docs/figures.md):
a step where every run diverged stays on the axis and says
so, a diverged run is drawn and named with its stop time, an all-zero metric is not an empty log
axis, lengths are in mm, step labels do not overlap, and every method gets its own panel."""
import math
from unittest import mock

import matplotlib.pyplot as plt
import numpy as np

from drapeanalysis import plots, plots_vibration, style
from drapeanalysis.figure_catalogue import CAPTIONS
from runfolder import RunFolderTest, write_energy, write_summary


class FigureTest(RunFolderTest):
    def drawn(self, make):
        """(stem, figure) of make(out_dir), the figure saved as the report saves it (log ticks,
        layout) but kept open for the test."""
        kept = []
        out = self.directory / "report"
        out.mkdir(exist_ok=True)
        with mock.patch.object(style.plt, "close", kept.append):
            stem = make(out)
        self.addCleanup(plt.close, "all")
        return stem, (kept[0] if kept else None)


def texts(fig):
    return [t.get_text() for ax in fig.axes for t in ax.texts]


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


class EnergyFigureTest(FigureTest):
    def energy_runs(self):
        """A reference, two leapfrog steps (the larger diverged at 0.006 s after one row) and a
        symplectic-Euler run, in a scene with a hold."""
        t = np.linspace(0.0, 1.0, 11)
        events = [{"t": 0.4, "type": "hold"}]
        rows = []
        for name, integrator, dt, status, times in (
                ("ref", "leapfrog", 2e-5, "ok", t), ("lf1", "leapfrog", 0.0002, "ok", t),
                ("lf2", "leapfrog", 0.002, "diverged", t[:1]), ("se", "symplectic-euler", 0.0002, "ok", t)):
            run = self.make_run(name)
            write_summary(run, events, status=status, sim_time=0.006 if status != "ok" else 1.0)
            write_energy(run, times, 1.0 + 0.01 * times)
            # sim_time in the row as in summary.json: merge copies it into results.json.
            rows.append(self.row(name, scene="scenes/s.json", integrator=integrator, status=status,
                                 sim_time=0.006 if status != "ok" else 1.0,
                                 **{"integrator.dt": dt}, events=1, is_reference=name == "ref"))
        return rows

    def test_a_diverged_run_is_drawn_to_its_end_with_an_x_and_its_stop_time(self):
        _, fig = self.drawn(lambda out: plots.energy_vs_time(self.directory, out, self.energy_runs(),
                                                             ["integrator.dt"]))
        leapfrog = next(ax for ax in fig.axes if ax.get_title() == "leapfrog")
        entries = [t.get_text() for t in leapfrog.get_legend().get_texts()]
        self.assertEqual(entries, ["dt=0.0002", "dt=0.002 (diverged at t = 0.006 s)"])
        stopped = [line for line in leapfrog.lines if line.get_marker() == style.FAILED_MARK]
        self.assertEqual(len(stopped), 1)
        self.assertEqual(list(stopped[0].get_xdata()), [0.0])
        self.assertEqual(stopped[0].get_markevery(), [0])
        # One row at t = 0: no change, drawn on the axis' floor.
        self.assertEqual(list(stopped[0].get_ydata()), [1e-8])

    def test_energy_by_scene_is_one_panel_per_integrator_each_with_the_reference(self):
        _, fig = self.drawn(lambda out: plots.energy_by_scene(self.directory, out, self.energy_runs(),
                                                              ["integrator.dt"]))
        panels = [ax for ax in fig.axes if ax.get_visible()]
        self.assertEqual([ax.get_title() for ax in panels], ["leapfrog", "symplectic-euler"])
        for ax in panels:
            entries = [t.get_text() for t in ax.get_legend().get_texts()]
            self.assertEqual(entries[0], "leapfrog dt=2e-05 (reference)")
            dashed = [line for line in ax.lines if line.get_linestyle() == "--" and line.get_color() == "k"]
            self.assertEqual(len(dashed), 1)
        self.assertIn("leapfrog dt=0.002 (diverged at t = 0.006 s)",
                      [t.get_text() for t in panels[0].get_legend().get_texts()])
        # E(t) - E(0) in mJ: 0.01 J over the second.
        reference = panels[1].lines[0]
        self.assertAlmostEqual(reference.get_ydata()[-1], 10.0)

    def test_the_caption_calls_the_energy_change_a_change_not_an_error(self):
        caption = CAPTIONS["energy_vs_time"]
        self.assertNotIn("energy error", caption)
        self.assertIn("Relative energy change", caption)
        self.assertIn("not an error", caption)

