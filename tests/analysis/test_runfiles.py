"""Bad run files: a clear error naming the file, or (for files a run may lack) no metric."""
import json
import tempfile
import unittest
from pathlib import Path

import numpy as np

import runfolder
from drapeanalysis import metrics, runfiles


class BadInputTest(unittest.TestCase):
    def setUp(self):
        self._tmp = tempfile.TemporaryDirectory()
        self.directory = Path(self._tmp.name)
        self.run = self.directory / "runs" / "a"
        self.run.mkdir(parents=True)
        self.row = {"id": "a", "run_dir": "runs/a"}

    def tearDown(self):
        self._tmp.cleanup()

    def assertNamesFile(self, error, path, *words):
        text = str(error.exception)
        self.assertIn(str(path), text)
        for word in words:
            self.assertIn(word, text)

    def test_missing_file(self):
        # A ValueError like every other bad input (the report's exit status 2), in drapelab's words.
        with self.assertRaises(ValueError) as error:
            runfiles.read_table(self.run / "energy.csv")
        self.assertNamesFile(error, self.run / "energy.csv", "no such file")
        with self.assertRaises(ValueError) as error:
            runfiles.read_trace(self.run / "trace.csv")
        self.assertNamesFile(error, self.run / "trace.csv", "no such file")

    def test_files_a_run_may_lack(self):
        # A diverged run has no state.csv, a run without a trace no trace.csv: no metric, no error.
        self.assertEqual(metrics.run_metrics(self.directory, self.row, {}), ({}, []), "no summary.json")
        runfolder.write_summary(self.run, [{"t": 0.1, "type": "map"}], status="diverged")
        out, windows = metrics.run_metrics(self.directory, {**self.row, "reference": "ref"},
                                           {"ref": {"id": "ref", "run_dir": "runs/ref"}})
        self.assertEqual((out, windows), ({}, []))

    def test_missing_column(self):
        runfolder.write_summary(self.run)
        runfolder.write_csv(self.run / "energy.csv", "t,kinetic,spring", [(0.0, 1.0, 2.0), (0.1, 1.0, 2.0)])
        with self.assertRaises(ValueError) as error:
            metrics.run_metrics(self.directory, self.row, {})
        self.assertNamesFile(error, self.run / "energy.csv", "total")

    def test_cut_last_line(self):
        # `head -c`: the last number is cut short, yet still a number; the missing newline shows it.
        (self.run / "energy.csv").write_text("t,total\n0,-1.5\n0.01,-1.49")
        with self.assertRaises(ValueError) as error:
            runfiles.read_energy(self.run / "energy.csv")
        self.assertNamesFile(error, self.run / "energy.csv", "the last line is cut")

    def test_energy_rows_ending_before_the_run(self):
        scene = {"output": {"energy_interval": 0.1}}
        runfolder.write_energy(self.run, [0.0, 0.1, 0.2], [-1.0, -1.0, -1.0])
        # A diverged run's last row lags its sim_time by up to an interval and a step.
        runfolder.write_summary(self.run, scene=scene, status="diverged", sim_time=0.32, step_max=0.025)
        summary = runfiles.read_summary(self.run)
        self.assertEqual(list(runfiles.read_run_energy(self.run, summary)["t"]), [0.0, 0.1, 0.2])
        summary["sim_time"] = 0.33
        with self.assertRaises(ValueError) as error:
            runfiles.read_run_energy(self.run, summary)
        self.assertNamesFile(error, self.run / "energy.csv", "the rows end at t = 0.2 s",
                             "sim_time = 0.33 s", "output.energy_interval = 0.1 s", "the file is cut")
        del summary["sim_time"]
        with self.assertRaises(ValueError) as error:
            runfiles.read_run_energy(self.run, summary)
        self.assertNamesFile(error, self.run / "summary.json", "no sim_time")

    def test_missing_state_column(self):
        runfolder.write_csv(self.run / "state.csv", "index,row,col,x,y", [(0, 0, 0, 1.0, 2.0)])
        ref = self.directory / "runs" / "ref"
        ref.mkdir()
        runfolder.write_state(ref, np.zeros((1, 3)))
        with self.assertRaises(ValueError) as error:
            metrics.reference_error(self.run, ref)
        self.assertNamesFile(error, self.run / "state.csv", "z")

    def test_trace_columns(self):
        runfolder.write_csv(self.run / "trace.csv", "t,index,x,y,z,vx,vy,vz,fixed,event",
                            [(0.0, 0, 0, 0, 0, 0, 0, 0, 0, 0)])
        with self.assertRaises(ValueError) as error:
            runfiles.read_trace(self.run / "trace.csv")
        self.assertNamesFile(error, self.run / "trace.csv", "contact")

    def test_truncated_trace(self):
        # Two particles, the last frame cut short.
        runfolder.write_csv(self.run / "trace.csv", runfolder.TRACE_HEADER,
                            [(0.0, 0, 0, 0, 0, 0, 0, 0, 0, -1, 0), (0.0, 1, 0, 0, 0, 0, 0, 0, 0, -1, 0),
                             (0.1, 0, 0, 0, 0, 0, 0, 0, 0, -1, 0)])
        with self.assertRaises(ValueError) as error:
            runfiles.read_trace(self.run / "trace.csv")
        self.assertNamesFile(error, self.run / "trace.csv")

    def test_not_a_number(self):
        runfolder.write_csv(self.run / "energy.csv", "t,total", [(0.0, 1.0), (0.1, "abc")])
        with self.assertRaises(ValueError) as error:
            runfiles.read_table(self.run / "energy.csv")
        self.assertNamesFile(error, self.run / "energy.csv")

    def test_no_rows_or_empty(self):
        runfolder.write_csv(self.run / "energy.csv", "t,total", [])
        with self.assertRaises(ValueError) as error:
            runfiles.read_table(self.run / "energy.csv", ("t", "total"))
        self.assertNamesFile(error, self.run / "energy.csv", "no rows")
        (self.run / "state.csv").write_text("")
        with self.assertRaises(ValueError) as error:
            runfiles.read_table(self.run / "state.csv")
        self.assertNamesFile(error, self.run / "state.csv", "empty")

    def test_bad_summary(self):
        (self.run / "summary.json").write_text('{"status": "ok", ')
        with self.assertRaises(ValueError) as error:
            metrics.run_metrics(self.directory, self.row, {})
        self.assertNamesFile(error, self.run / "summary.json")

    def test_hands_missing_column(self):
        runfolder.write_csv(self.run / "hands.csv", "t,hand,x,y,z", [(0.0, "left", 0.0, 0.0, 0.0)])
        with self.assertRaises(ValueError) as error:
            runfiles.read_hands(self.run / "hands.csv")
        self.assertNamesFile(error, self.run / "hands.csv", "available")

    def test_reference_of_another_size(self):
        ref = self.directory / "runs" / "ref"
        ref.mkdir()
        runfolder.write_state(self.run, np.zeros((4, 3)))
        runfolder.write_state(ref, np.zeros((5, 3)))
        with self.assertRaises(ValueError) as error:
            metrics.reference_error(self.run, ref)
        self.assertNamesFile(error, self.run / "state.csv")
        self.assertIn(str(ref / "state.csv"), str(error.exception))

    def test_grid_size_not_matching_state(self):
        runfolder.write_summary(self.run, [{"t": 0.1, "type": "map"}],
                                {"cloth": {"rows": 2, "cols": 3, "spacing": 0.1}})
        runfolder.write_state(self.run, np.zeros((4, 3)))
        runfolder.write_csv(self.run / "dummy.csv", "index,section,point,x,y,z,nx,ny,nz",
                            [(0, 0, 0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0)])
        with self.assertRaises(ValueError) as error:
            metrics.mapping_error(self.run, runfiles.read_json(self.run / "summary.json"))
        self.assertNamesFile(error, self.run / "state.csv", "2 x 3")


class DocumentTest(runfolder.RunFolderTest):
    """results.json and summary.json without a field the analysis reads, or with a value of the
    wrong type there: a ValueError naming the file and the field (was a KeyError or TypeError)."""

    RESULTS = {"name": "n", "question": "q", "metrics": [], "parameters": ["integrator.dt"], "plan_size": 1,
               "columns": ["id", "run_dir"], "runs": [{"id": "a", "run_dir": "runs/a"}]}

    def assertRefused(self, name, doc, message, read):
        (self.directory / name).write_text(json.dumps(doc))
        with self.assertRaises(ValueError) as error:
            read(self.directory)
        self.assertEqual(str(error.exception), f"{self.directory / name}: {message}")

    def test_results_json(self):
        runs = self.RESULTS["runs"]
        for doc, message in (
                ([], "expected a JSON object, got a list"),
                ({k: v for k, v in self.RESULTS.items() if k != "runs"}, "runs: missing"),
                ({**self.RESULTS, "parameters": "integrator.dt"}, 'parameters: expected a list of strings, got "integrator.dt"'),
                ({**self.RESULTS, "columns": ["id", 3]}, "columns: expected a list of strings, got 3"),
                ({**self.RESULTS, "plan_size": True}, "plan_size: expected an integer, got true"),
                ({**self.RESULTS, "runs": [1]}, "runs: expected a list of objects, got 1"),
                ({**self.RESULTS, "runs": [{"run_dir": "runs/a"}]}, "runs[0].id: expected a non-empty string, got null"),
                ({**self.RESULTS, "runs": [{"id": "a", "run_dir": ""}]}, 'runs[0].run_dir: expected a non-empty string, got ""'),
                ({**self.RESULTS, "runs": [{"id": "../a", "run_dir": "runs/a"}]},
                 "runs[0].id: '../a' is not a file name (it names the run's animation and viewer page)"),
                ({**self.RESULTS, "runs": runs + runs}, "runs[1].id: 'a' repeats an earlier run's id")):
            with self.subTest(message):
                self.assertRefused("results.json", doc, message, runfiles.load_experiment)
        (self.directory / "results.json").write_text(json.dumps(self.RESULTS))
        self.assertEqual(runfiles.load_experiment(self.directory), self.RESULTS)

    def test_summary_json(self):
        for doc, message in (
                ("ok", 'expected a JSON object, got a string'),
                ({"events": {}}, "events: expected a list, got an object"),
                ({"events": [[]]}, "events[0]: expected an object, got a list"),
                ({"events": [{"t": 0.1}]}, "events[0].type: expected a string, got null"),
                ({"events": [{"t": 0.1, "type": "hold"}, {"t": "0.2", "type": "release"}]},
                 'events[1].t: expected a finite number, got "0.2"')):
            with self.subTest(message):
                self.assertRefused("summary.json", doc, message, runfiles.read_summary)
        # NaN is not JSON, but Python's json reads it.
        (self.directory / "summary.json").write_text('{"events": [{"t": NaN, "type": "hold"}]}')
        with self.assertRaises(ValueError) as error:
            runfiles.read_summary(self.directory)
        self.assertIn("events[0].t: expected a finite number, got NaN", str(error.exception))

    def test_summary_numbers_the_energy_check_reads(self):
        runfolder.write_energy(self.directory, [0.0, 0.1], [-1.0, -1.0])
        for summary, message in (({"sim_time": None}, "sim_time: expected a finite number, got null"),
                                 ({"sim_time": 0.1, "step_max": "x"}, 'step_max: expected a finite number, got "x"'),
                                 ({"sim_time": 0.1, "scene": {"output": {"energy_interval": []}}},
                                  "scene.output.energy_interval: expected a finite number, got []")):
            with self.subTest(message), self.assertRaises(ValueError) as error:
                runfiles.read_run_energy(self.directory, summary)
            self.assertEqual(str(error.exception), f"{self.directory / 'summary.json'}: {message}")


if __name__ == "__main__":
    unittest.main()
