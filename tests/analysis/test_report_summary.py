"""The report's summary (drapeanalysis/report_summary.py, docs/analysis.md): method x scene
cells of mean +- the Student-t 95 % half-width over an ensemble's repeats, what a cell says for
runs that did not finish or never fixed an attach, and the banner naming the unfinished runs."""
import math
import unittest

import runfolder  # noqa: F401  (puts analysis/ on the path)
from drapeanalysis import report_summary


class ReportSummaryTest(unittest.TestCase):
    def test_summary_tables_group_the_repeats_of_an_ensemble(self):
        # Three repeats (seeds 1-3) of one method: one row, mean 20 mm +- t(0.975, 2) 10 / sqrt 3.
        rows = [{"id": f"r{k}", "scene": "scenes/s.json", "integrator": "leapfrog", "integrator.dt": 0.001,
                 "perturbation.seed": k, "attach_error_mean": 0.01 * k, "status": "ok"} for k in (1, 2, 3)]
        page = report_summary.summary_tables(rows, ["integrator.dt", "perturbation.seed"])
        self.assertIn("20 &plusmn; 25&dagger; (n=3)", page)  # 2 - 2.5 < 0: marked
        self.assertNotIn("seed=", page)

    def test_summary_tables_give_diverged_runs_a_dash_and_count_the_runs_with_a_value(self):
        # Two diverged repeats whose drift reads 0 (they blew up before their first energy row)
        # and two finished ones of which only one held: a dash, and "n=1 of 2", not a bare mean.
        def run(k, method, status, **metrics):
            return {"id": f"{method}{k}", "scene": "scenes/s.json", "integrator": method,
                    "dt": 0.002, "perturbation.seed": k, "status": status, **metrics}
        rows = [run(1, "leapfrog", "diverged", energy_drift_max_rel=0.0, wall_seconds=1e-4),
                run(2, "leapfrog", "diverged", energy_drift_max_rel=0.0, wall_seconds=1e-4),
                run(1, "implicit-euler", "ok", energy_drift_max_rel=0.2, vibration_rms_after_hold=0.004),
                run(2, "implicit-euler", "ok", energy_drift_max_rel=0.4)]
        page = report_summary.summary_tables(rows, ["perturbation.seed"])
        drift = page[page.index("energy"):]
        self.assertIn("<tr><th>leapfrog dt=0.002</th><td>diverged (2 of 2)</td></tr>", drift)
        # 0.3 +- 1.3 reaches below 0: the dagger says the mean of 2 values is not well determined.
        self.assertIn("<td>0.3 &plusmn; 1.3&dagger; (n=2)</td>", drift)
        self.assertIn("<td>4 (n=1 of 2)</td>", page)
        self.assertNotIn("<td>0</td>", page)

    def test_a_cell_counts_the_runs_that_did_not_finish(self):
        # Three repeats, one failed: "n=2 of 3; 1 did not finish"; the interval 1.5 +- 6.4 of
        # {1, 2} (t(0.975, 1) = 12.706, s = 0.707) reaches below 0 and is marked.
        rows = [{"id": f"r{k}", "scene": "scenes/s.json", "integrator": "leapfrog", "dt": 0.001,
                 "perturbation.seed": k, "status": status, "wall_seconds": w}
                for k, (status, w) in enumerate((("ok", 1.0), ("ok", 2.0), ("failed", 9.0)))]
        page = report_summary.summary_tables(rows, ["perturbation.seed"])
        self.assertIn("<td>1.5 &plusmn; 6.4&dagger; (n=2 of 3; 1 did not finish)</td>", page)

    def test_the_banner_names_every_run_that_did_not_finish(self):
        rows = [{"id": "a", "scene": "scenes/s.json", "integrator": "leapfrog", "dt": 0.002,
                 "status": "diverged", "sim_time": 0.006, "duration": 1.0,
                 "reason": "runaway: a particle moves at 888 m/s"},
                {"id": "b", "scene": "scenes/s.json", "integrator": "leapfrog", "dt": 0.0002,
                 "status": "ok", "sim_time": 1.0, "duration": 1.0}]
        banner = report_summary.unfinished_banner(rows, [])
        self.assertIn("<b>1 of 2 runs did not finish</b> (diverged)", banner)
        self.assertIn("<td>leapfrog dt=0.002</td><td>s</td><td>diverged</td><td>0.006 s of 1 s</td>"
                      "<td>runaway: a particle moves at 888 m/s</td>", banner)
        self.assertEqual(report_summary.unfinished_banner(rows[1:], []), "")
        many = [dict(rows[0], id=str(k)) for k in range(report_summary.BANNER_ROWS + 1)]
        self.assertIn("<details><summary>the 9 runs</summary>", report_summary.unfinished_banner(many, []))

    def test_method_names_carry_the_swept_values_but_not_the_scene_or_the_seed(self):
        row = {"scene": "scenes/s.json", "integrator": "vbd", "integrator.dt": 0.002, "cloth.k_bending": 5,
               "perturbation.seed": 3}
        self.assertEqual(report_summary.method_name(row, ["integrator.dt", "scene"]), "vbd dt=0.002")
        self.assertEqual(report_summary.method_name(row, ["integrator.dt", "cloth.k_bending"]),
                         "vbd dt=0.002, k_bending=5")
        self.assertEqual(report_summary.method_name(dict(row, is_reference=True), []), "vbd dt=0.002 (reference)")

    def test_an_attach_note_only_for_an_attachs_metrics(self):
        row = {"attach_unfixed_count": 2}
        self.assertEqual(report_summary.attach_note(row, "attach_error_mean"), "2 not fixed")
        self.assertEqual(report_summary.attach_note(row, "wall_seconds"), "")
        self.assertEqual(report_summary.attach_note({"attach_unfixed_count": 0}, "attach_error_mean"), "")
        self.assertEqual(report_summary.attach_note({}, "attach_error_mean"), "")

    def test_the_stop_word_is_diverged_only_when_every_run_diverged(self):
        self.assertEqual(report_summary.stop_word(["diverged", "diverged"]), "diverged")
        self.assertEqual(report_summary.stop_word(["diverged", "failed"]), "did not finish")
        self.assertEqual(report_summary.unfinished([{"status": "ok"}, {"status": "error"}, {}]),
                         [{"status": "error"}, {}])
        self.assertEqual(report_summary.summary_tables([], []), "")


if __name__ == "__main__":
    unittest.main()
