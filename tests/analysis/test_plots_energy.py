"""The energy figures (drapeanalysis/plots_energy.py, docs/figures.md) on synthetic runs: a
diverged run drawn to its end and named with its stop time, one panel per integrator each with
the reference, the caption calling the energy change a change."""
import unittest

import numpy as np

from figure_test import FigureTest  # first: puts analysis/ on the path
from drapeanalysis import plots, style
from drapeanalysis.figure_catalogue import CAPTIONS
from runfolder import write_energy, write_summary


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

if __name__ == "__main__":
    unittest.main()
