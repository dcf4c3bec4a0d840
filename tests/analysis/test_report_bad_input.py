"""report.py on bad input, end to end (docs/analysis.md, "Bad input and failed writes"): an
input that is a named pipe or a folder is exit status 2 naming the path, and never blocks the
report."""
import contextlib
import json
import os
import tempfile
import unittest
from pathlib import Path

import numpy as np
from PIL import Image

import runfolder


class ReportTestCase(unittest.TestCase):
    """A fresh synthetic experiment (runfolder.write_experiment) per test."""

    def setUp(self):
        self._tmp = tempfile.TemporaryDirectory()
        self.directory = Path(self._tmp.name) / "exp"
        self.directory.mkdir()
        self.runs = runfolder.write_experiment(self.directory)
        self.run = self.directory / self.runs[0]["run_dir"]

    def tearDown(self):
        self._tmp.cleanup()

    def report(self, *args, status, message, **kwargs):
        """Runs the report; checks its exit status and that stderr holds `message`, without a
        traceback."""
        done = runfolder.run_report(self.directory, *args, **kwargs)
        self.assertEqual(done.returncode, status, done.stderr)
        self.assertIn(message, done.stderr)
        self.assertNotIn("Traceback", done.stderr)
        return done

    def assertNothingWritten(self):
        self.assertFalse((self.directory / "metrics.csv").exists())
        self.assertFalse((self.directory / "report").exists())

    def assertNoReportPage(self):
        """No report.html and no temporary or cut file: every file left is whole."""
        self.assertFalse((self.directory / "report" / "report.html").exists())
        left = [p for p in self.directory.rglob("*") if p.is_file() and "runs" not in p.parts]
        self.assertFalse([p for p in left if p.name.startswith(".")], "temporaries removed")
        for path in left:
            if path.suffix == ".png":
                with Image.open(path) as png:
                    png.load()  # a cut PNG raises here
            if path.suffix == ".json":
                json.loads(path.read_text())


@contextlib.contextmanager
def replaced(path, make):
    """The file `path` replaced by what make(path) makes (a named pipe, a folder) inside the
    block, and put back after it."""
    kept = path.read_bytes()
    path.unlink()
    make(path)
    try:
        yield
    finally:
        if path.is_dir():
            path.rmdir()
        else:
            path.unlink()
        path.write_bytes(kept)


class InputNotARegularFileTest(ReportTestCase):
    """Defect 1: every input the report opens, a named pipe in its place, used to block the
    report for ever; a folder in its place was a traceback."""

    def test_a_named_pipe_in_place_of_any_input_is_refused(self):
        # The optional inputs too: the event trace and the hands.
        runfolder.write_event_trace(self.run, [0.0, 0.001, 0.002], np.zeros((3, 12, 3)))
        runfolder.write_hands(self.run, [(0.0, "right", 1, 0.0, 1.0, 0.0)])
        for path in [self.directory / "results.json"] + [self.run / name for name in (
                "summary.json", "energy.csv", "trace.csv", "hands.csv", "event_trace/t.npy", "dummy.csv")]:
            with self.subTest(path.name), replaced(path, os.mkfifo):
                self.report(status=2, message=f"{path}: not a regular file", timeout=60)
                self.assertNoReportPage()

    def test_a_folder_in_place_of_an_input_is_refused(self):
        for name in ("summary.json", "energy.csv", "trace.csv"):
            path = self.run / name
            with self.subTest(name), replaced(path, os.mkdir):
                self.report(status=2, message=f"{path}: is a directory, not a file")
                self.assertNothingWritten()


if __name__ == "__main__":
    unittest.main()
