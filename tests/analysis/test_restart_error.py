"""The restart error's columns (docs/analysis.md, "Restart error") from a restart_error.csv with
known values: means over the event branches, per kind, relative to the reference's motion, later
horizons, and failed branches counted and left out."""
import math

from drapeanalysis import metrics, plots
from runfolder import RunFolderTest, write_summary

HEADER = "t,events,horizon,status,error_rms,error_max,reference_motion_rms\n"
ROWS = [
    "0,start,0.0333333,ok,0.001,0.002,0.01",
    "0,start,0.1,ok,0.002,0.004,0.02",
    "0.4,hold,0.0333333,ok,0.004,0.01,0.02",
    "0.4,hold,0.1,ok,0.01,0.03,0.05",
    "1.5,release,0.0333333,ok,0.002,0.005,0.04",
    "1.5,release,0.1,ok,0.006,0.01,0.1",
    "1.9,hold,0.0333333,failed,nan,nan,0.01",
    "1.9,hold,0.1,failed,nan,nan,0.03",
]


class RestartErrorTest(RunFolderTest):
    def test_means_over_the_events_by_kind_and_horizon(self):
        run = self.make_run("restarts")
        (run / "restart_error.csv").write_text(HEADER + "\n".join(ROWS) + "\n")
        out = metrics.restart_error(run, {})
        self.assertAlmostEqual(out["restart_error_start"], 0.001)
        self.assertAlmostEqual(out["restart_error_events"], (0.004 + 0.002) / 2)
        self.assertAlmostEqual(out["restart_error_after_hold"], 0.004)
        self.assertAlmostEqual(out["restart_error_after_release"], 0.002)
        self.assertTrue(math.isnan(out["restart_error_after_attach"]))
        self.assertAlmostEqual(out["restart_error_events_rel"], (0.004 / 0.02 + 0.002 / 0.04) / 2)
        self.assertAlmostEqual(out["restart_motion_events"], (0.02 + 0.04) / 2)
        self.assertAlmostEqual(out["restart_error_events_100ms"], (0.01 + 0.006) / 2)
        self.assertAlmostEqual(out["restart_error_after_hold_100ms"], 0.01)
        self.assertAlmostEqual(out["restart_error_after_release_100ms"], 0.006)
        self.assertNotIn("restart_error_after_attach_100ms", out)
        self.assertEqual(out["restart_error_failed"], 2)

    def test_no_file_no_columns_and_a_bad_cell_is_named(self):
        run = self.make_run("none")
        self.assertEqual(metrics.restart_error(run, {}), {})
        (run / "restart_error.csv").write_text(HEADER + "0,start,0.0333333,ok,abc,0.1,0.1\n")
        with self.assertRaisesRegex(ValueError, r"restart_error.csv: row 1, column error_rms"):
            metrics.restart_error(run, {})

    def test_figure_skips_a_run_whose_event_branches_all_failed(self):
        good, failed = self.make_run("good"), self.make_run("failed")
        (good / "restart_error.csv").write_text(HEADER + "\n".join(ROWS) + "\n")
        (failed / "restart_error.csv").write_text(HEADER + ROWS[0] + "\n" + ROWS[-1] + "\n")
        for run in (good, failed):
            write_summary(run, sim_time=2.0)
        rows = [self.row("good", integrator="leapfrog", dt=1e-4, scene="s.json"),
                self.row("failed", integrator="implicit-euler", dt=0.01, scene="s.json")]
        out = self.directory / "report"
        out.mkdir()
        self.assertEqual(plots.restart_error_vs_horizon(self.directory, out, rows, []),
                         "restart_error_vs_horizon")
        self.assertTrue((out / "restart_error_vs_horizon.png").exists())
        self.assertIsNone(plots.restart_error_vs_horizon(self.directory, out, rows[1:], []))
