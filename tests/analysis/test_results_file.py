"""An experiment's results.json read for a report (drapeanalysis/results_file.py,
docs/experiments.md "The table"): a ValueError naming the file and the field for a document the
analysis cannot read, the plan experiment.json holds, and the runs' files all there."""
import json
import unittest

import runfolder
from drapeanalysis import results_file


class ResultsFileTest(runfolder.RunFolderTest):
    RESULTS = {"name": "n", "question": "q", "metrics": [], "parameters": ["integrator.dt"], "plan_size": 1,
               "columns": ["id", "run_dir"], "runs": [{"id": "a", "run_dir": "runs/a", "status": "ok"}]}

    def assertRefused(self, name, doc, message, read):
        (self.directory / name).write_text(json.dumps(doc))
        with self.assertRaises(ValueError) as error:
            read(self.directory)
        self.assertEqual(str(error.exception), f"{self.directory / name}: {message}")

    def assertIncomplete(self, message):
        with self.assertRaises(ValueError) as error:
            results_file.load_complete_experiment(self.directory)
        self.assertEqual(str(error.exception), message)

    def test_results_json(self):
        runs = self.RESULTS["runs"]
        for doc, message in (
                ([], "expected a JSON object, got a list"),
                ({k: v for k, v in self.RESULTS.items() if k != "runs"}, "runs: missing"),
                ({**self.RESULTS, "parameters": "integrator.dt"}, 'parameters: expected a list of strings, got "integrator.dt"'),
                ({**self.RESULTS, "columns": ["id", 3]}, "columns: expected a list of strings, got 3"),
                ({**self.RESULTS, "plan_size": True}, "plan_size: expected an integer, got true"),
                ({**self.RESULTS, "plan_size": 0}, "plan_size: 0, but runs lists 1 runs (merge writes at most the plan's runs)"),
                ({**self.RESULTS, "plan_size": -1}, "plan_size: -1, but runs lists 1 runs (merge writes at most the plan's runs)"),
                ({**self.RESULTS, "metrics": ["vibration", "vibrations"]},
                 'metrics[1]: unknown metric "vibrations" (known: attach_error, energy_drift, mapping_error, '
                 'restart_error, snapshots, stable_dt, vibration, work_precision)'),
                ({**self.RESULTS, "runs": [1]}, "runs: expected a list of objects, got 1"),
                ({**self.RESULTS, "runs": [{"run_dir": "runs/a", "status": "ok"}]}, "runs[0].id: expected a non-empty string, got null"),
                ({**self.RESULTS, "runs": [{"id": "a", "run_dir": "", "status": "ok"}]}, 'runs[0].run_dir: expected a non-empty string, got ""'),
                ({**self.RESULTS, "runs": [{"id": "../a", "run_dir": "runs/a", "status": "ok"}]},
                 "runs[0].id: '../a' is not a file name (it names the run's animation and viewer page)"),
                ({**self.RESULTS, "runs": runs + runs}, "runs[1].id: 'a' repeats an earlier run's id"),
                ({**self.RESULTS, "runs": [{"id": "a", "run_dir": "runs/a", "status": "banana"}]},
                 'runs[0].status: expected one of ok, diverged, failed, error, crashed, got "banana"'),
                ({**self.RESULTS, "runs": [{"id": "a", "run_dir": "runs/a"}]},
                 "runs[0].status: expected one of ok, diverged, failed, error, crashed, got null"),
                # drapelab writes null, never nan: the report blanked a nan without a word.
                ({**self.RESULTS, "runs": [{**runs[0], "wall_seconds": float("nan")}]},
                 "runs[0].wall_seconds: not a finite number (drapelab writes null, never nan or inf)"),
                ({**self.RESULTS, "runs": [{**runs[0], "energy_final": "nan"}]},
                 'runs[0].energy_final: expected a number or null, got "nan"'),
                ({**self.RESULTS, "runs": [{**runs[0], "counters": {"steps": float("inf")}}]},
                 "runs[0].counters.steps: not a finite number (drapelab writes null, never nan or inf)")):
            with self.subTest(message):
                self.assertRefused("results.json", doc, message, results_file.load_experiment)
        (self.directory / "results.json").write_text(json.dumps(self.RESULTS))
        self.assertEqual(results_file.load_experiment(self.directory), self.RESULTS)

    def test_results_of_another_plan_than_experiment_json(self):
        # A resumed experiment stopped before it wrote its table left the last one's beside a
        # plan of three runs; the report showed the two old runs as the experiment.
        (self.directory / "results.json").write_text(json.dumps(self.RESULTS))
        plan = {"plan_size": 1, "plan": [{"id": "a"}]}
        (self.directory / "experiment.json").write_text(json.dumps(plan))
        results_file.check_plan(self.directory, self.RESULTS)
        for header, stale in (({"plan_size": 3, "plan": [{"id": "a"}, {"id": "b"}, {"id": "c"}]},
                               "results.json plans 1 runs, experiment.json 3"),
                              ({"plan_size": 1, "plan": [{"id": "b"}]},
                               "results.json's run 'a' is not in experiment.json's plan")):
            (self.directory / "experiment.json").write_text(json.dumps(header))
            with self.subTest(stale), self.assertRaises(ValueError) as error:
                results_file.check_plan(self.directory, self.RESULTS)
            self.assertEqual(str(error.exception), f"{self.directory}: {stale}: the table is of another "
                             "invocation (one stopped before it wrote its own); run `drapelab experiment` "
                             "again to finish it, then report")
        (self.directory / "experiment.json").write_text(json.dumps({"plan_size": "1"}))
        with self.assertRaises(ValueError) as error:
            results_file.check_plan(self.directory, self.RESULTS)
        self.assertIn("experiment.json: expected plan_size (an integer) and plan (a list)", str(error.exception))

    def test_the_first_non_finite_number_is_named_by_its_path(self):
        self.assertIsNone(results_file.non_finite({"a": [1, 2.5, None, "nan"], "b": {"c": 0.0}}))
        self.assertEqual(results_file.non_finite({"a": [1, float("inf")]}), "a[1]")
        self.assertEqual(results_file.non_finite({"runs": [{"x": 1.0}, {"y": {"z": float("nan")}}]}),
                         "runs[1].y.z")
        self.assertEqual(results_file.non_finite([float("-inf")]), "[0]")

    def test_a_complete_experiment_has_every_planned_run_with_its_files(self):
        runs = runfolder.write_experiment(self.directory)
        self.assertEqual([row["id"] for row in results_file.load_complete_experiment(self.directory)["runs"]],
                         [row["id"] for row in runs])
        (self.directory / "runs" / runs[1]["id"] / "energy.csv").unlink()
        (self.directory / "runs" / runs[2]["id"] / "state.csv").unlink()
        self.assertIncomplete(
            f"{self.directory}: runs listed in results.json lack their files: "
            f"{self.directory / 'runs' / runs[1]['id'] / 'energy.csv'}, "
            f"{self.directory / 'runs' / runs[2]['id'] / 'state.csv'} (remove such a run's result.json "
            "and rerun `drapelab experiment` to redo it)")

    def test_a_folder_that_holds_no_whole_table_is_named(self):
        missing = self.directory / "none"
        with self.assertRaises(ValueError) as error:
            results_file.load_complete_experiment(missing)
        self.assertEqual(str(error.exception), f"{missing}: no such folder")
        (self.directory / "summary.json").write_text("{}")
        self.assertIncomplete(f"{self.directory}: a run's folder, not an experiment's: no results.json "
                              "(run `drapelab experiment` or `drapelab merge` first)")
        (self.directory / "results.json").write_text(json.dumps({**self.RESULTS, "runs": []}))
        self.assertIncomplete(f"{self.directory / 'results.json'}: no runs (an experiment with an empty plan, "
                              "or a merge before any shard finished)")
        (self.directory / "results.json").write_text(json.dumps({**self.RESULTS, "plan_size": 4}))
        self.assertIncomplete(
            f"{self.directory / 'results.json'}: 1 of 4 planned runs have a result (a merge that named "
            "missing runs, or an experiment that was stopped): run the rest (`drapelab experiment` "
            "resumes, shards run again) and `drapelab merge`, then report")

    def test_the_table_keeps_the_documents_column_order(self):
        doc = {**self.RESULTS, "columns": ["status", "id", "run_dir"],
               "runs": [{"id": "a", "run_dir": "runs/a", "status": "ok", "extra": 1},
                        {"id": "b", "run_dir": "runs/b", "status": "diverged", "extra": 2}], "plan_size": 2}
        (self.directory / "results.json").write_text(json.dumps(doc))
        table = results_file.results_table(self.directory)
        self.assertEqual(list(table.columns), ["status", "id", "run_dir", "extra"])
        self.assertEqual(list(table["status"]), ["ok", "diverged"])


if __name__ == "__main__":
    unittest.main()
