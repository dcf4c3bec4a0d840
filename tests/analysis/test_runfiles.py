"""Bad run files: a clear error naming the file, or (for files a run may lack) no metric."""
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


if __name__ == "__main__":
    unittest.main()
