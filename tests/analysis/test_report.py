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


class ReportTableTest(unittest.TestCase):
    def test_metrics_files(self):
        with tempfile.TemporaryDirectory() as tmp:
            directory = Path(tmp)
            for name in ("a", "b"):
                (directory / "runs" / name).mkdir(parents=True)
            run_a = directory / "runs" / "a"
            events = [{"t": 0.1, "type": "attach_fixed", "attach_error": 0.002},
                      {"t": 0.2, "type": "attach_fixed", "attach_error": 0.004}]
            runfolder.write_summary(run_a, events)
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

    def test_example_redraws_a_figure(self):
        out = self.directory / "example" / "energy_b"
        run_script(ANALYSIS / "examples" / "redraw_figure.py", self.directory, "--scene", "b", "--out", out)
        for fmt in ("png", "svg", "pdf"):
            self.assertTrue(out.with_suffix(f".{fmt}").stat().st_size > 0)
