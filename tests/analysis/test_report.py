"""report.py's table: the results row (attach error from summary.json events, computed when the
experiment writes results.json) kept, the analysis metrics added, missing values empty/null."""
import csv
import json
import math
import tempfile
import unittest
from pathlib import Path

import numpy as np

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
