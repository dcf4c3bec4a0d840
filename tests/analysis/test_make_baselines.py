"""make_baselines.py (docs/experiments.md, the energy-drift regression): the baselines from an
experiment's results, the reviewed tolerances of existing entries kept, new entries given the
defaults, nothing written when a run did not finish."""
import json
import shutil
import subprocess
import sys
import unittest

import runfolder

SCRIPT = runfolder.ANALYSIS_DIR / "make_baselines.py"
BASELINES = runfolder.ANALYSIS_DIR.parent / "tests" / "regression" / "energy_drift_baselines.json"


def results_of(baselines):
    """The results.json an experiment would write for these baselines: one row per entry, its
    overrides as parameters, the expected values as its metrics."""
    parameters = sorted({key for entry in baselines["runs"] for key in entry["overrides"]})
    runs = [{"id": f"run{k}", "status": "ok", "scene": entry["scene"], **entry["overrides"],
             **{metric: expected["value"] for metric, expected in entry["expect"].items()}}
            for k, entry in enumerate(baselines["runs"])]
    return {"parameters": parameters, "runs": runs}


class MakeBaselinesTest(runfolder.RunFolderTest):
    def make(self, results, baselines):
        (self.directory / "results.json").write_text(json.dumps(results))
        return subprocess.run([sys.executable, str(SCRIPT), str(self.directory), str(baselines)],
                              capture_output=True, text=True, timeout=60)

    def test_the_shipped_baselines_are_a_fixed_point(self):
        shipped = json.loads(BASELINES.read_text())
        copy = self.directory / "baselines.json"
        shutil.copy(BASELINES, copy)
        done = self.make(results_of(shipped), copy)
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertEqual(done.stdout.strip(), f"{copy}: {len(shipped['runs'])} baselines")
        self.assertEqual(json.loads(copy.read_text()), shipped)

    def test_reviewed_tolerances_are_kept_and_new_entries_get_the_defaults(self):
        old = {"runs": [{"scene": "scenes/a.json", "overrides": {"integrator.name": "vbd"},
                         "expect": {"energy_drift_max_rel": {"value": 1.0, "rel_tol": 0.5},
                                    "steps": {"value": 10, "pct_tol": 3}}}]}
        baselines = self.directory / "baselines.json"
        baselines.write_text(json.dumps(old))
        metrics = {"energy_drift_max_rel": 0.25, "energy_drift_final_rel": 0.125, "steps": 40, "rhs_evals": 41}
        rows = [{"id": "a", "status": "ok", "scene": "scenes/a.json", "integrator.name": "vbd", **metrics},
                {"id": "b", "status": "ok", "scene": "scenes/a.json", "integrator.name": "xpbd", **metrics}]
        done = self.make({"parameters": ["integrator.name", "integrator.dt"], "runs": rows}, baselines)
        self.assertEqual(done.returncode, 0, done.stderr)
        kept, new = json.loads(baselines.read_text())["runs"]
        self.assertEqual(kept["overrides"], {"integrator.name": "vbd"}, "a parameter the row lacks is left out")
        self.assertEqual(kept["expect"]["energy_drift_max_rel"], {"value": 0.25, "rel_tol": 0.5})
        self.assertEqual(kept["expect"]["steps"], {"value": 40, "pct_tol": 3})
        self.assertEqual(kept["expect"]["rhs_evals"], {"value": 41, "pct_tol": 0})
        self.assertEqual(new["expect"], {"energy_drift_max_rel": {"value": 0.25, "rel_tol": 0.05},
                                         "energy_drift_final_rel": {"value": 0.125, "rel_tol": 0.2},
                                         "steps": {"value": 40, "pct_tol": 0},
                                         "rhs_evals": {"value": 41, "pct_tol": 0}})

    def test_runs_that_did_not_finish_write_nothing(self):
        baselines = self.directory / "baselines.json"
        rows = [{"id": "a", "status": "ok"}, {"id": "b", "status": "diverged"}, {"id": "c", "status": "error"}]
        done = self.make({"parameters": [], "runs": rows}, baselines)
        self.assertEqual(done.returncode, 1)
        self.assertEqual(done.stderr.strip(), f"{self.directory}: runs not ok, no baselines written: b, c")
        self.assertFalse(baselines.exists())


if __name__ == "__main__":
    unittest.main()
