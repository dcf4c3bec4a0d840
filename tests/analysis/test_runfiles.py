"""Bad run files: a clear error naming the file, or (for files a run may lack) no metric."""
import json
import shutil
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


class ValueTest(runfolder.RunFolderTest):
    """Values no run writes (docs/outputs.md): inf, times that do not increase, a flag that is
    not 0 or 1, an unknown status; a ValueError naming the file, the row and the column (they
    were read, and the metrics changed or became nan)."""

    def setUp(self):
        super().setUp()
        self.run = self.make_run()

    def assertRefused(self, read, path, message):
        with self.assertRaises(ValueError) as error:
            read()
        self.assertEqual(str(error.exception), f"{path}: {message}")

    def test_inf_in_a_csv_file(self):
        path = self.run / "energy.csv"
        for cell, shown in (("inf", "inf"), ("-inf", "-inf"), ("1e999", "'1e999'")):
            with self.subTest(cell):
                runfolder.write_csv(path, "t,total", [(0.0, 1.0), (0.1, cell)])
                self.assertRefused(lambda: runfiles.read_energy(path), path,
                                   f"row 2, column total: not a finite number ({shown})")
        # A column that may hold nan (not measured) may not hold inf.
        path = self.run / "restart_error.csv"
        header = "t,events,horizon,status,error_rms,error_max,reference_motion_rms"
        runfolder.write_csv(path, header, [(0.0, "start", 0.01, "reference_failed", "nan", "nan", "nan")])
        self.assertEqual(len(runfiles.read_restart_error(path)), 1)
        runfolder.write_csv(path, header, [(0.0, "start", 0.01, "ok", "inf", 0.0, 0.0)])
        self.assertRefused(lambda: runfiles.read_restart_error(path), path,
                           "row 1, column error_rms: not a finite number (inf)")

    def test_energy_times_that_do_not_increase(self):
        path = self.run / "energy.csv"
        for t, message in (([0.0, 0.1, 0.1, 0.2], "row 3, column t: t = 0.10000000000000001 is not after the time "
                                                  "before it, t = 0.10000000000000001 (times must increase)"),
                           ([0.0, 0.1, -3.0], "row 3, column t: t = -3 is not after the time before it, "
                                              "t = 0.10000000000000001 (times must increase)")):
            with self.subTest(t):
                runfolder.write_energy(self.run, t, [-1.0] * len(t))
                self.assertRefused(lambda: runfiles.read_energy(path), path, message)

    def trace(self, t=(0.0, 0.1, 0.2), **columns):
        """A trace of two particles at times t."""
        x = np.zeros((len(t), 2, 3))
        runfolder.write_trace(self.run, t, x, **columns)
        return self.run / "trace.csv"

    def test_trace_times_that_do_not_increase(self):
        path = self.trace()
        self.assertEqual(list(runfiles.trace_frames(runfiles.read_trace(path))["t"]), [0.0, 0.1, 0.2])
        path = self.trace([0.0, 0.1, 0.1])
        self.assertRefused(lambda: runfiles.read_trace(path), path,
                           "row 5, column t: t = 0.10000000000000001 is not after the time before it, "
                           "t = 0.10000000000000001 (times must increase)")
        path = self.trace([0.0, -1.0, 0.2])
        self.assertRefused(lambda: runfiles.read_trace(path), path,
                           "row 3, column t: t = -1 is not after the time before it, t = 0 (times must increase)")
        # A frame whose rows disagree on the time, or lists its particles out of order.
        text = path.read_text().splitlines()
        text[2] = "0.5" + text[2][1:]
        path.write_text("\n".join(text) + "\n")
        self.assertRefused(lambda: runfiles.read_trace(path), path,
                           "row 2: particle 1 at t = 0.5, expected particle 1 of the frame at t = 0 "
                           "(a frame lists every particle in order at one time)")

    def test_trace_flags_other_than_0_or_1(self):
        fixed = np.zeros((3, 2), int)
        fixed[1, 1] = 7
        path = self.trace(fixed=fixed)
        self.assertRefused(lambda: runfiles.read_trace(path), path, "row 4, column fixed: 7, expected 0 or 1")
        path = self.trace(event=np.array([1, 0, 2]))
        self.assertRefused(lambda: runfiles.read_trace(path), path, "row 5, column event: 2, expected 0 or 1")

    def test_restart_error_status_and_horizon(self):
        path = self.run / "restart_error.csv"
        header = "t,events,horizon,status,error_rms,error_max,reference_motion_rms"
        ok = (0.0, "start", 0.01, "ok", 1e-6, 2e-6, 1e-3)
        for status in ("ok", "reference_diverged", "reference_failed", "diverged", "failed"):
            measured = ok[4:] if status == "ok" else ("nan", "nan", "nan")  # an ok branch measured
            runfolder.write_csv(path, header, [ok, (0.1, "hold", 0.01, status) + measured])
            self.assertEqual(list(runfiles.read_restart_error(path)["status"]), ["ok", status])
        runfolder.write_csv(path, header, [ok, (0.1, "hold", 0.01, "banana", "nan", "nan", "nan")])
        self.assertRefused(lambda: runfiles.read_restart_error(path), path,
                           "row 2, column status: expected one of ok, reference_diverged, reference_failed, "
                           'diverged, failed, got "banana"')
        runfolder.write_csv(path, header, [ok, (0.1, "hold", -0.01, "ok", 0.0, 0.0, 0.0)])
        self.assertRefused(lambda: runfiles.read_restart_error(path), path,
                           "row 2, column horizon: -0.01, expected a positive time")

    def event_trace(self, t=(0.0, 0.001, 0.002), x=None):
        """event_trace/ of two particles at rest; its folder."""
        x = np.zeros((len(t), 2, 3)) if x is None else x
        runfolder.write_event_trace(self.run, t, x)
        return self.run / "event_trace"

    def test_event_trace_values(self):
        folder = self.event_trace()
        self.assertEqual(list(runfiles.read_event_trace(self.run)["t"]), [0.0, 0.001, 0.002])
        for t, message in (([0.0, 0.002, 0.001], "index [2]: t = 0.001 is not after the time before it, t = 0.002 "
                                                 "(times must increase)"),
                           ([0.0, 0.001, 0.001], "index [2]: t = 0.001 is not after the time before it, t = 0.001 "
                                                 "(times must increase)"),
                           ([0.0, np.nan, 0.002], "index [1]: not a finite number (nan)")):
            with self.subTest(t):
                shutil.rmtree(folder)
                self.event_trace(t)
                self.assertRefused(lambda: runfiles.read_event_trace(self.run), folder / "t.npy", message)
        shutil.rmtree(folder)
        x = np.zeros((3, 2, 3))
        x[2, 1, 0] = np.inf
        self.event_trace(x=x)
        self.assertRefused(lambda: runfiles.read_event_trace(self.run), folder / "x.npy",
                           "index [2, 1, 0]: not a finite number (inf)")
        shutil.rmtree(folder)
        self.event_trace()
        np.save(folder / "fixed.npy", np.array([[0, 1], [1, 7], [0, 0]], np.uint8))
        self.assertRefused(lambda: runfiles.read_event_trace(self.run), folder / "fixed.npy",
                           "index [1, 1]: 7, expected 0 or 1")
        np.save(folder / "fixed.npy", np.zeros((3, 2), np.uint8))
        np.save(folder / "v.npy", np.full((3, 2, 3), "x"))
        self.assertRefused(lambda: runfiles.read_event_trace(self.run), folder / "v.npy",
                           "<U1 values, expected float32")
        np.save(folder / "v.npy", np.zeros((3, 2, 3), np.float32))
        np.save(folder / "t.npy", np.array([0, 1, 2], np.int64))  # milliseconds, say
        self.assertRefused(lambda: runfiles.read_event_trace(self.run), folder / "t.npy",
                           "int64 values, expected float64")


class DocumentTest(runfolder.RunFolderTest):
    """summary.json without a field the analysis reads, or with a value of the wrong type there:
    a ValueError naming the file and the field (results.json's: test_results_file.py)."""

    def assertRefused(self, name, doc, message, read):
        (self.directory / name).write_text(json.dumps(doc))
        with self.assertRaises(ValueError) as error:
            read(self.directory)
        self.assertEqual(str(error.exception), f"{self.directory / name}: {message}")

    def test_summary_json(self):
        ok = {"status": "ok"}
        for doc, message in (
                ("ok", 'expected a JSON object, got a string'),
                ({"status": "banana"}, 'status: expected one of ok, diverged, failed, got "banana"'),
                ({"events": []}, "status: expected one of ok, diverged, failed, got null"),
                # error and crashed are results.json's, for runs that wrote no summary.
                ({"status": "error"}, 'status: expected one of ok, diverged, failed, got "error"'),
                (ok | {"events": {}}, "events: expected a list, got an object"),
                (ok | {"events": [[]]}, "events[0]: expected an object, got a list"),
                (ok | {"events": [{"t": 0.1}]}, "events[0].type: expected a string, got null"),
                (ok | {"events": [{"t": 0.1, "type": "hold"}, {"t": "0.2", "type": "release"}]},
                 'events[1].t: expected a finite number, got "0.2"')):
            with self.subTest(message):
                self.assertRefused("summary.json", doc, message, runfiles.read_summary)
        for status in ("ok", "diverged", "failed"):
            (self.directory / "summary.json").write_text(json.dumps({"status": status}))
            self.assertEqual(runfiles.read_summary(self.directory)["status"], status)
        # NaN is not JSON, but Python's json reads it.
        (self.directory / "summary.json").write_text('{"status": "ok", "events": [{"t": NaN, "type": "hold"}]}')
        with self.assertRaises(ValueError) as error:
            runfiles.read_summary(self.directory)
        self.assertIn("events[0].t: expected a finite number, got NaN", str(error.exception))

    def test_the_files_a_summary_says_its_run_wrote(self):
        self.assertEqual(runfiles.optional_run_files(self.directory, {"status": "diverged"}), [])
        scene = {"input": {"events": []},
                 "output": {"trace_interval": 0.01, "event_trace_interval": 0.001}}
        summary = {"status": "ok", "object_particles": 24, "scene": scene, "restart_error": {}}
        arrays = [f"event_trace/{name}.npy" for name in ("t", "x", "v", "fixed", "contact")]
        self.assertEqual(runfiles.optional_run_files(self.directory, summary),
                         ["state.csv", "dummy.csv", "hands.csv", "trace.csv", *arrays,
                          "restart_error.csv"])
        with self.assertRaises(ValueError) as error:
            runfiles.optional_run_files(self.directory,
                                        {"scene": {"output": {"trace_interval": "x"}}})
        self.assertEqual(str(error.exception), f"{self.directory / 'summary.json'}: "
                         'scene.output.trace_interval: expected a finite number, got "x"')


if __name__ == "__main__":
    unittest.main()
