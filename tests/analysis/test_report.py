"""report.py's table: the results row (attach error from summary.json events, computed when the
experiment writes results.json) kept, the analysis metrics added, missing values empty/null."""
import csv
import json
import math
import os
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

import numpy as np
from PIL import Image

import runfolder
import report
from drapeanalysis import report_summary, results_file


class ReportTableTest(unittest.TestCase):
    def test_metrics_files(self):
        with tempfile.TemporaryDirectory() as tmp:
            directory = Path(tmp)
            for name in ("a", "b"):
                (directory / "runs" / name).mkdir(parents=True)
            run_a = directory / "runs" / "a"
            events = [{"t": 0.1, "type": "attach_fixed", "attach_error": 0.002},
                      {"t": 0.2, "type": "attach_fixed", "attach_error": 0.004}]
            runfolder.write_summary(run_a, events, sim_time=1.0)
            t = np.linspace(0.0, 1.0, 11)
            runfolder.write_energy(run_a, t, -2.0 * (1 + 0.1 * t))
            runfolder.write_summary(directory / "runs" / "b", status="diverged")
            results = {
                "name": "t", "question": "q", "metrics": [], "parameters": [], "plan_size": 2,
                "columns": ["id", "run_dir", "status", "attach_count", "attach_error_mean", "attach_error_max"],
                "runs": [
                    {"id": "a", "run_dir": "runs/a", "status": "ok", "attach_count": 2,
                     "attach_error_mean": 0.003, "attach_error_max": 0.004},
                    {"id": "b", "run_dir": "runs/b", "status": "diverged", "attach_count": 0,
                     "attach_error_mean": None, "attach_error_max": None},
                ],
            }
            rows, windows = report.add_metrics(directory, results)
            self.assertEqual(rows[0]["attach_error_mean"], 0.003)
            self.assertTrue(math.isclose(rows[0]["energy_drift_rate"], 0.1, rel_tol=1e-9))
            self.assertEqual(windows, {})
            rows[0]["energy_drift_exponent"] = math.nan
            report.write_metrics(directory, results, rows, windows)
            with open(directory / "metrics.csv", newline="") as f:
                table = list(csv.DictReader(f))
            self.assertEqual(float(table[0]["attach_error_mean"]), 0.003)
            self.assertEqual(float(table[0]["attach_error_max"]), 0.004)
            self.assertTrue(math.isclose(float(table[0]["energy_drift_max_rel"]), 0.1, rel_tol=1e-9))
            self.assertEqual(table[0]["energy_drift_exponent"], "", "nan: empty cell")
            self.assertEqual(table[1]["attach_error_mean"], "")
            self.assertEqual(table[1]["energy_drift_max_rel"], "", "diverged run without energy.csv")
            doc = json.loads((directory / "metrics.json").read_text())
            self.assertIsNone(doc["runs"][0]["energy_drift_exponent"])
            self.assertEqual(doc["runs"][0]["attach_error_max"], 0.004)


if __name__ == "__main__":
    unittest.main()


ANALYSIS = Path(__file__).resolve().parents[2] / "analysis"


def run_script(script, *args):
    """Runs an analysis script with this tree's drapeanalysis, failing the test on an error."""
    env = {**os.environ, "PYTHONPATH": str(ANALYSIS), "PYTHONDONTWRITEBYTECODE": "1"}
    done = subprocess.run([sys.executable, str(script), *map(str, args)], env=env, capture_output=True,
                          text=True, timeout=300)
    if done.returncode:
        raise AssertionError(f"{script} failed ({done.returncode}):\n{done.stderr}")
    return done.stdout


class ReportEndToEndTest(unittest.TestCase):
    """report.py on a small synthetic experiment: figures in three formats, the summary with
    units, the full table folded, an animation on request; the example script redraws a figure."""

    @classmethod
    def setUpClass(cls):
        cls._tmp = tempfile.TemporaryDirectory()
        cls.directory = Path(cls._tmp.name)
        cls.runs = runfolder.write_experiment(cls.directory)
        run_script(ANALYSIS / "report.py", cls.directory, "--frames", 12, "--animate", cls.runs[0]["id"])
        cls.report = cls.directory / "report"

    @classmethod
    def tearDownClass(cls):
        cls._tmp.cleanup()

    def test_figures_in_three_formats(self):
        stems = {p.stem for p in self.report.glob("*.png")}
        for stem in ("energy_vs_time", "energy_by_scene", "vibration_vs_dt", "snapshots_a_front",
                     "snapshots_a_side", "snapshots_b_front"):
            self.assertIn(stem, stems)
        for stem in stems:
            for fmt in ("svg", "pdf"):
                self.assertTrue((self.report / f"{stem}.{fmt}").stat().st_size > 0, f"{stem}.{fmt}")
            with Image.open(self.report / f"{stem}.png") as png:
                self.assertGreaterEqual(round(png.info["dpi"][0]), 200, stem)

    def test_html(self):
        page = (self.report / "report.html").read_text()
        self.assertIn("<h2>Summary</h2>", page)
        self.assertIn("Vibration over the last 0.5 s [mm]", page)
        self.assertIn("<details><summary>", page)
        self.assertLess(page.index("<h2>Summary</h2>"), page.index("<details>"))
        for stem in ("energy_by_scene", "snapshots_b_side"):
            self.assertIn(f'src="{stem}.png"', page)
            self.assertIn(f"href='{stem}.pdf'", page)
        self.assertIn(f"<video controls src='{self.runs[0]['id']}.mp4'", page)

    def test_metrics_of_the_synthetic_runs(self):
        # The last 0.5 s: a 40 Hz sinusoid of amplitude (1 + k) mm on the free particles, above
        # the 3 x 4 cloth's cutoff (15.2 Hz); the 0.8 Hz swing below it.
        with open(self.directory / "metrics.csv", newline="") as f:
            table = {row["id"]: row for row in csv.DictReader(f)}
        for k, run in enumerate(self.runs[:2]):
            got = float(table[run["id"]]["vibration_rms_final"])
            self.assertTrue(math.isclose(got, (1 + k) * 1e-3 / math.sqrt(2), rel_tol=0.01), got)
            self.assertTrue(math.isclose(float(table[run["id"]]["vibration_cutoff_hz"]), 15.2, rel_tol=0.01))

    def test_animation(self):
        movie = (self.report / f"{self.runs[0]['id']}.mp4").read_bytes()
        self.assertGreater(len(movie), 1000)
        self.assertEqual(movie[4:8], b"ftyp", "an MP4 container")

    def test_the_experiments_metrics_choose_the_figures(self):
        # `metrics: ["energy_drift"]` (docs/experiments.md): the energy figures, no vibration
        # figures and no snapshots (which cost a large report a third of its time).
        out = self.directory / "only_energy"
        out.mkdir()
        results = results_file.load_experiment(self.directory)
        stems = [stem for stem, _ in report.make_figures(self.directory, out, results["runs"],
                                                         results["parameters"], ("energy_drift",))]
        self.assertIn("energy_vs_time", stems)
        self.assertFalse([s for s in stems if s.startswith(("vibration", "snapshots"))], stems)

    def test_example_redraws_a_figure(self):
        out = self.directory / "example" / "energy_b"
        run_script(ANALYSIS / "examples" / "redraw_figure.py", self.directory, "--scene", "b", "--out", out)
        for fmt in ("png", "svg", "pdf"):
            self.assertTrue(out.with_suffix(f".{fmt}").stat().st_size > 0)


class ReportBadInputTest(unittest.TestCase):
    def test_a_malformed_run_file_is_named_with_exit_2(self):
        with tempfile.TemporaryDirectory() as tmp:
            runs = runfolder.write_experiment(Path(tmp))
            energy = Path(tmp) / runs[0]["run_dir"] / "energy.csv"
            energy.write_text("x\n1\n")
            done = self.report(tmp)
            self.assertEqual(done.returncode, 2, done.stderr)
            self.assertIn(f"{energy}: missing column(s) t, total", done.stderr)

    def report(self, directory):
        done = runfolder.run_report(directory)
        self.assertNotIn("Traceback", done.stderr)
        return done

    def test_a_run_whose_files_are_gone_is_refused_not_reported(self):
        with tempfile.TemporaryDirectory() as tmp:
            runs = runfolder.write_experiment(Path(tmp))
            run = Path(tmp) / runs[1]["run_dir"]
            (run / "summary.json").unlink()
            (run / "energy.csv").unlink()
            done = self.report(tmp)
            self.assertEqual(done.returncode, 2, done.stderr)
            self.assertIn(f"runs listed in results.json lack their files: {run / 'summary.json'}, "
                          f"{run / 'energy.csv'} (remove", done.stderr)
            self.assertFalse((Path(tmp) / "report").exists())

    def test_a_file_the_summary_says_the_run_wrote_is_required(self):
        # Each dropped its metrics or figures silently (state.csv: the error against the
        # reference; trace.csv: the vibration, with a note blaming output.trace_interval = 0).
        with tempfile.TemporaryDirectory() as tmp:
            runs = runfolder.write_experiment(Path(tmp))
            run = Path(tmp) / runs[0]["run_dir"]
            summary = json.loads((run / "summary.json").read_text())
            summary["scene"].update(input={"events": []}, output={"trace_interval": 0.005})
            (run / "summary.json").write_text(json.dumps({**summary, "object_particles": 24}))
            hands = [(t, "right", 1, 0.0, 1.0, 0.2) for t in np.linspace(0, 1, 11)]
            runfolder.write_hands(run, hands)
            for name in ("state.csv", "dummy.csv", "trace.csv", "hands.csv"):
                with self.subTest(name):
                    kept = (run / name).read_bytes()
                    (run / name).unlink()
                    self.assertRefused(tmp, f"lack their files: {run / name} (remove")
                    (run / name).write_bytes(kept)

    def assertRefused(self, directory, message):
        """report.py exits 2 with `message` and writes no report."""
        done = self.report(directory)
        self.assertEqual(done.returncode, 2, done.stderr)
        self.assertIn(message, done.stderr)
        self.assertFalse((Path(directory) / "report").exists())

    def test_a_cut_energy_csv_is_refused(self):
        with tempfile.TemporaryDirectory() as tmp:
            runs = runfolder.write_experiment(Path(tmp))
            energy = Path(tmp) / runs[0]["run_dir"] / "energy.csv"
            whole = energy.read_bytes()
            # `head -c 300`: later rows gone, the last number cut; then the same cut at a row's end.
            energy.write_bytes(whole[:300])
            self.assertRefused(tmp, f"{energy}: the last line is cut")
            energy.write_bytes(whole[:whole.rindex(b"\n", 0, 300) + 1])
            self.assertRefused(tmp, f"{energy}: the rows end at t = 0.025 s, before the run's sim_time = 1 s")

    def test_an_experiment_without_runs_is_refused(self):
        with tempfile.TemporaryDirectory() as tmp:
            runfolder.write_experiment(Path(tmp))
            results = json.loads((Path(tmp) / "results.json").read_text())
            results["runs"] = []
            (Path(tmp) / "results.json").write_text(json.dumps(results))
            self.assertRefused(tmp, f"{Path(tmp) / 'results.json'}: no runs")

    def test_a_missing_folder_a_file_and_a_run_folder_are_refused_with_exit_2(self):
        with tempfile.TemporaryDirectory() as tmp:
            a_file, run = Path(tmp) / "a_file", Path(tmp) / "run"
            a_file.write_text("x")
            run.mkdir()
            runfolder.write_summary(run)
            for directory, message in ((Path(tmp) / "nope", "nope: no such folder"),
                                       (a_file, "a_file: not a folder"),
                                       (Path(tmp), f"{tmp}: no results.json"),
                                       (run, "run: a run's folder, not an experiment's: no results.json")):
                done = self.report(directory)
                self.assertEqual(done.returncode, 2, done.stderr)
                self.assertIn(message, done.stderr)


class ReportProvenanceAndViewerTest(unittest.TestCase):
    """The provenance block from the results rows, the runs paired side by side in the viewer,
    and the viewer links of report.html (the pages themselves: report_viewer_check.py)."""

    ROW = {"version": "0.9.0", "git_commit": "abc123", "build_type": "Release", "sundials_version": "6.4.1",
           "machine.hostname": "lab1", "machine.cpu": "Xeon", "machine.cores": 8}

    def test_provenance_names_every_field_and_counts_mixed_values(self):
        rows = [dict(self.ROW, id="a", date="2026-11-23T22:01:23Z"),
                dict(self.ROW, id="b", date="2026-11-23T22:05:00Z", **{"machine.hostname": "lab2"}),
                dict(self.ROW, id="c", date="2026-11-23T22:03:00Z", git_commit="abc123-dirty")]
        page = report.provenance_html(rows)
        for text in ("<th>drapelab version</th><td>0.9.0</td>", "<th>build type</th><td>Release</td>",
                     "<th>SUNDIALS version</th><td>6.4.1</td>", "<th>cores</th><td>8</td>",
                     "<td>lab1 (2 runs); lab2 (1 run)</td>", "<td>abc123 (2 runs); abc123-dirty (1 run)</td>",
                     "<th>runs started</th><td>2026-11-23T22:01:23Z to 2026-11-23T22:05:00Z</td>",
                     "uncommitted changes"):
            self.assertIn(text, page)
        self.assertIn("<th>CPU</th><td>not recorded</td>", report.provenance_html([{"id": "x"}]))

    def test_an_attach_never_fixed_is_not_a_dash(self):
        # Two finished repeats: one fixed its attach (4 mm), one ended before fixing it; a third
        # method never fixed one at all. A dash stays for "does not apply" only.
        def run(k, method, unfixed, error):
            return {"id": f"{method}{k}", "scene": "scenes/s.json", "integrator": method, "dt": 0.001,
                    "perturbation.seed": k, "status": "ok", "attach_unfixed_count": unfixed,
                    "attach_error_mean": error}
        rows = [run(1, "leapfrog", 0, 0.004), run(2, "leapfrog", 1, math.nan),
                run(1, "implicit-euler", 1, math.nan), run(2, "implicit-euler", 1, math.nan)]
        page = report_summary.summary_tables(rows, ["perturbation.seed"])
        self.assertIn("<td>4 (n=1 of 2; 1 not fixed)</td>", page)
        self.assertIn("<td>not fixed (2 of 2)</td>", page)
        table = report.html_table(rows, ["perturbation.seed"])
        self.assertIn("<td>4</td>", table)  # 0.004 m in the table's mm
        self.assertIn("<td>1 not fixed</td>", table)

    def test_a_point_from_some_of_an_ensembles_runs_says_how_many(self):
        # Two repeats at each step: both finite at 1 ms, one diverged (no value) at 2 ms, none
        # finite at 4 ms. The 2 ms point is the one value and says "1 of 2"; 4 ms has no point.
        from drapeanalysis import plots
        points = [(0.001, 1.0), (0.001, 3.0), (0.002, 5.0), (0.002, math.nan),
                  (0.004, math.nan), (0.004, math.nan)]
        stats = plots.with_intervals(points)
        self.assertEqual([(x, y, n, runs) for x, y, _, n, runs in stats],
                         [(0.001, 2.0, 2, 2), (0.002, 5.0, 1, 2)])
        rows = [{"id": f"{k}{seed}", "scene": "scenes/s.json", "integrator": "leapfrog",
                 "integrator.dt": x, "perturbation.seed": seed, "vibration_rms_final": y}
                for k, (seed, (x, y)) in enumerate(zip([1, 2] * 3, points))]
        import matplotlib.pyplot as plt
        from unittest import mock
        texts = []
        real_save = plots.style.save
        def keep_texts(fig, out_dir, stem):
            texts.extend(t.get_text() for ax in fig.axes for t in ax.texts)
            return real_save(fig, out_dir, stem)
        with tempfile.TemporaryDirectory() as tmp, mock.patch.object(plots.style, "save", keep_texts):
            self.assertEqual(plots.vibration_vs_dt(Path(tmp), rows, ["integrator.dt", "perturbation.seed"]),
                             "vibration_vs_dt")
            plt.close("all")
        self.assertEqual(texts, ["1 of 2", "no value (2 of 2)"])  # 4 ms: no value in either run

    def test_a_field_solvers_attach_error_is_drawn_against_its_work_per_step(self):
        # leap-frog's attach iterations 1 and 10; xpbd's substeps 10 and 20 (1 iteration each)
        # and vbd's iterations 5 at one attach iteration: the solvers only in their own figure.
        def run(integrator, attach, error, **keys):
            return {"id": f"{integrator}{attach}{keys}", "scene": "scenes/fig4.json", "integrator": integrator,
                    "integrator.name": integrator, "manipulation.attach_iterations": attach,
                    "dt": 1 / 30, "attach_error_mean": error, "status": "ok"} | keys
        rows = [run("leapfrog", 1, 0.01, **{"integrator.dt": 2e-4}),
                run("leapfrog", 10, 0.02, **{"integrator.dt": 2e-4}),
                run("xpbd", 1, 0.03, **{"integrator.substeps": 10, "integrator.iterations": 1}),
                run("xpbd", 1, 0.04, **{"integrator.substeps": 20, "integrator.iterations": 1}),
                run("vbd", 1, 0.05, **{"integrator.iterations": 5})]
        self.assertTrue(math.isnan(report.solver_work(rows[0])))
        self.assertEqual([report.solver_work(r) for r in rows[2:]], [10, 20, 5])
        parameters = ["integrator.name", "integrator.dt", "integrator.substeps", "integrator.iterations",
                      "manipulation.attach_iterations"]
        import matplotlib.pyplot as plt
        from unittest import mock
        from drapeanalysis import plots
        drawn = {}
        real_save = plots.style.save
        def keep_lines(fig, out_dir, stem):
            drawn[stem] = {bars.get_label(): list(bars.lines[0].get_xdata()) for ax in fig.axes
                           for bars in ax.containers}
            return real_save(fig, out_dir, stem)
        with tempfile.TemporaryDirectory() as tmp, mock.patch.object(plots.style, "save", keep_lines):
            stems = [stem for stem, _ in report.make_figures(Path(tmp), Path(tmp), rows, parameters,
                                                             ("attach_error",))]
            plt.close("all")
        self.assertEqual(stems, ["attach_error_vs_iterations", "attach_error_vs_solver_work",
                                 "attach_error_vs_time"])
        self.assertEqual(len(drawn["attach_error_vs_iterations"]), 1)  # leap-frog's line alone
        solver_lines = drawn["attach_error_vs_solver_work"]
        self.assertEqual(len(solver_lines), 2)
        np.testing.assert_allclose(sorted(x for xs in solver_lines.values() for x in xs), [5, 10, 20],
                                   rtol=0.2)  # series at the same x are dodged

    def test_html_links_the_viewer_pages_and_says_why_a_run_has_none(self):
        rows = [dict(id="a", scene="scenes/s.json", integrator="leapfrog", **{"integrator.dt": 0.001}),
                dict(id="b", scene="scenes/s.json", integrator="implicit-euler", **{"integrator.dt": 0.002}),
                dict(id="c", scene="scenes/s.json", integrator="leapfrog", **{"integrator.dt": 0.002})]
        pages = ({"a": "view/a.html", "b": "view/b.html"},
                 {"c": "no page: no trace.csv (output.trace_interval = 0)"},
                 {"s": ("view/scenes/s.html", rows[:2])})
        results = {"name": "n", "question": "q", "parameters": ["integrator.dt"]}
        with tempfile.TemporaryDirectory() as tmp:
            report.write_html(Path(tmp), results, rows, [("snapshots_s_front", "caption")], pages=pages)
            page = (Path(tmp) / "report.html").read_text()
            report.write_html(Path(tmp), results, rows, [])
            without = (Path(tmp) / "report.html").read_text()
        self.assertIn("<h2>Provenance</h2>", page)
        self.assertIn("<a href='view/scenes/s.html'>side by side: leapfrog dt=0.001 | implicit-euler dt=0.002</a>",
                      page)
        self.assertIn("<a href='view/a.html'>leapfrog dt=0.001</a>", page)
        self.assertIn("PDF</a>, <a href='view/scenes/s.html'>in 3-D</a></figcaption>", page)
        self.assertIn("<td>a</td><td><a href='view/a.html'>view</a></td>", page)
        self.assertIn("<td>c</td><td>no page: no trace.csv (output.trace_interval = 0)</td>", page)
        self.assertIn("Runs without a page: 1 run, no trace.csv (output.trace_interval = 0)", page)
        self.assertLess(page.index("<h2>3-D viewer</h2>"), page.index("<h2>Figures</h2>"))
        self.assertIn("No viewer pages: report.py ran without --drapelab", without)
        self.assertNotIn("<th>3-D</th>", without)
