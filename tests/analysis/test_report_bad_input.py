"""report.py on bad input and failed writes, end to end (docs/analysis.md, "Bad input"): an
input that is a named pipe or a folder, an option out of its range and a malformed document are
exit status 2 naming the path or the option; a write that fails (a file size limit, a read-only
folder, `drapelab view` unable to write a page) is exit status 4 naming the file, and leaves no
half file and no report.html."""
import contextlib
import io
import json
import os
import resource
import signal
import tempfile
import unittest
from pathlib import Path

import numpy as np
from PIL import Image

import runfolder
from drapeanalysis import report_options


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

    def only_figures(self, *metrics):
        """The experiment's `metrics` (docs/experiments.md) set to ask for these figures only
        ("stable_dt": none this data has), for a quicker report."""
        results = json.loads((self.directory / "results.json").read_text())
        (self.directory / "results.json").write_text(json.dumps({**results, "metrics": list(metrics)}))

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
    """Every input the report opens, with a named pipe in its place, would block the report
    for ever, and a folder in its place would be a traceback: both are named."""

    def test_a_named_pipe_in_place_of_any_input_is_refused(self):
        # The optional inputs too: the event trace and the hands.
        runfolder.write_event_trace(self.run, [0.0, 0.5, 1.0], np.zeros((3, 12, 3)))  # to the run's end
        runfolder.write_hands(self.run, [(t, "right", 1, 0.0, 1.0, 0.0) for t in (0.0, 1.0)])
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


def file_size_limit(size):
    """A preexec_fn: writes past `size` bytes fail with EFBIG (SIGXFSZ ignored, as `ulimit -f`
    under a shell that ignores it; Python ignores it too)."""
    def limit():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (size, size))
    return limit


class FailedWriteTest(ReportTestCase):
    """Defect 2: a write that failed left a half file (metrics, figures, the page) and a folder
    that looked finished; a file in place of the report's folder was a traceback."""

    def test_a_file_size_limit_at_the_metrics(self):
        # metrics.json is about 9 kB.
        self.report(status=4, message=f"cannot write {self.directory / 'metrics.json'}: File too large",
                    preexec_fn=file_size_limit(4000))
        self.assertFalse((self.directory / "metrics.json").exists())
        self.assertNoReportPage()

    def test_a_file_size_limit_at_a_figure_removes_the_previous_report_page(self):
        # The metrics fit in 40 kB, the first figure's PNG (about 60 kB) does not.
        (self.directory / "report").mkdir()
        (self.directory / "report" / "report.html").write_text("a previous report")
        done = self.report(status=4, message=f"cannot write {self.directory / 'report' / 'energy_vs_time.png'}: "
                           "File too large", preexec_fn=file_size_limit(40000))
        self.assertFalse((self.directory / "report" / "energy_vs_time.png").exists(), done.stderr)
        self.assertNoReportPage()

    def test_an_animation_cut_by_a_file_size_limit(self):
        # No figures: the metrics fit in 12 kB, an MP4 of 20 frames (about 25 kB) does not.
        # ffmpeg gets SIGXFSZ (Python starts it with the default action).
        self.only_figures("stable_dt")
        out = self.directory / "report" / f"{self.runs[0]['id']}.mp4"
        self.report("--animate", self.runs[0]["id"], "--frames", 20, status=4,
                    message=f"cannot write {out}: File too large", preexec_fn=file_size_limit(12000))
        self.assertFalse(out.exists())
        self.assertNoReportPage()

    def test_a_file_where_the_report_folder_goes(self):
        # Bad input, not a failed write: exit 2, before anything is written.
        (self.directory / "report").write_text("x")
        self.report(status=2, message=f"{self.directory / 'report'}: not a folder")
        self.assertFalse((self.directory / "metrics.csv").exists())

    @unittest.skipIf(os.geteuid() == 0, "root writes into a read-only folder")
    def test_a_read_only_experiment_folder(self):
        self.directory.chmod(0o555)
        try:
            # Bad input, named before any work (not exit 4 from the first write).
            self.report(status=2, message=f"{self.directory}: cannot be written (Permission denied): "
                                          "the report writes its files there")
        finally:
            self.directory.chmod(0o755)
        self.assertNothingWritten()

    def test_a_viewer_page_drapelab_could_not_write(self):
        # `drapelab view` says exit 4 for a page it could not write; the report must not list
        # that run as merely having no page.
        fake = Path(self._tmp.name) / "drapelab"
        fake.write_text('#!/bin/sh\necho "drapelab: cannot write $4: No space left on device" >&2\nexit 4\n')
        fake.chmod(0o755)
        self.only_figures("stable_dt")
        page = self.directory / "report" / "view" / f"{self.runs[0]['id']}.html"
        self.report("--drapelab", fake, status=4,
                    message=f"{page}: drapelab view failed (drapelab: cannot write {page}: No space left on device)")
        self.assertNoReportPage()


class OptionRangeTest(ReportTestCase):
    """Defect 3: --frames took any integer; --animate ids that name nothing, or runs without a
    trace, were skipped silently or exited 1 after the report was written."""

    def test_frames_out_of_range(self):
        for value in ("-1", "0", "1", "100001", "1000000000000", "nan", "inf", "2.5", "1e3", ""):
            with self.subTest(value), contextlib.redirect_stderr(io.StringIO()) as stderr:
                with self.assertRaises(SystemExit) as done:
                    report_options.parse("", [str(self.directory), "--animate", f"--frames={value}"])
                self.assertEqual(done.exception.code, 2)
                self.assertIn(f"argument --frames: expected a whole number from 2 to 100000, got {value!r}",
                              stderr.getvalue())
        # The same end to end, before anything is written.
        self.report("--animate", "--frames", "-1", status=2,
                    message="argument --frames: expected a whole number from 2 to 100000, got '-1'")
        self.assertNothingWritten()
        self.assertEqual(report_options.parse("", [str(self.directory), "--animate", "--frames", "2"]).frames, 2)
        self.assertEqual(report_options.parse("", [str(self.directory), "--animate"]).frames, 300)

    def test_frames_without_animate(self):
        self.report("--frames", "10", status=2, message="--frames: only with --animate")
        self.assertNothingWritten()

    def test_animate_names_no_run_or_a_run_without_a_trace(self):
        self.report("--animate", "nope", self.runs[0]["id"], status=2,
                    message=f"--animate: no run nope in {self.directory / 'results.json'}")
        self.assertNothingWritten()
        (self.run / "trace.csv").unlink()
        self.report("--animate", self.runs[0]["id"], status=2,
                    message=f"--animate: run {self.runs[0]['id']} has no trace.csv")
        self.assertNothingWritten()
        for run in self.runs[1:]:
            (self.directory / run["run_dir"] / "trace.csv").unlink()
        self.report("--animate", status=2, message="--animate: no run has a trace.csv")
        self.assertNothingWritten()

    def test_drapelab_that_is_no_program(self):
        not_a_program = self.directory / "results.json"
        for path, words in ((self.directory / "nope", "no such file"), (not_a_program, "not executable"),
                            (self.directory, "is a directory, not a file")):
            with self.subTest(str(path)):
                self.report("--drapelab", path, status=2, message=f"--drapelab {path}: {words}")
                self.assertNothingWritten()

    def test_animate_without_ffmpeg(self):
        # Not bad input but a missing program: exit 1 as `drapelab report` without its Python.
        no_programs = Path(self._tmp.name) / "bin"
        no_programs.mkdir()
        self.report("--animate", status=1, message="--animate needs ffmpeg", env={"PATH": str(no_programs)})
        self.assertNothingWritten()

    def test_an_empty_folder_name(self):
        done = runfolder.run_report("")
        self.assertEqual(done.returncode, 2, done.stderr)
        self.assertIn("an empty path", done.stderr)


class MalformedDocumentTest(ReportTestCase):
    """A document the report reads without the field it needs, or with a value out of range,
    was a traceback (KeyError, TypeError, numpy's reshape)."""

    def test_results_json_without_a_field(self):
        results = json.loads((self.directory / "results.json").read_text())
        del results["parameters"]
        (self.directory / "results.json").write_text(json.dumps(results))
        self.report(status=2, message=f"{self.directory / 'results.json'}: parameters: missing")
        self.assertNothingWritten()

    def test_results_json_with_fewer_runs_than_the_plan(self):
        # what `drapelab merge` leaves when runs are missing (it exits 1 and names them): a
        # report of the runs that are there looked like the experiment's whole
        results = json.loads((self.directory / "results.json").read_text())
        results["plan_size"] = len(results["runs"]) + 2
        (self.directory / "results.json").write_text(json.dumps(results))
        self.report(status=2, message=f"{self.directory / 'results.json'}: {len(results['runs'])} of "
                                      f"{len(results['runs']) + 2} planned runs have a result")
        self.assertNothingWritten()

    def test_summary_json_with_a_bad_event_time(self):
        summary = json.loads((self.run / "summary.json").read_text())
        summary["events"][1]["t"] = None
        (self.run / "summary.json").write_text(json.dumps(summary))
        self.report(status=2, message=f"{self.run / 'summary.json'}: events[1].t: expected a finite number, got null")
        self.assertNothingWritten()

    def test_bad_input_removes_the_previous_report_page(self):
        # Refused while reading the runs, before any figure: the last report.html stayed, and
        # the folder looked reported on its old files.
        (self.directory / "report").mkdir()
        (self.directory / "report" / "report.html").write_text("a previous report")
        summary = json.loads((self.run / "summary.json").read_text())
        summary["events"][1]["t"] = None
        (self.run / "summary.json").write_text(json.dumps(summary))
        self.report(status=2, message=f"{self.run / 'summary.json'}: events[1].t")
        self.assertNoReportPage()

    def test_a_cloth_grid_that_is_not_the_trace(self):
        summary = json.loads((self.run / "summary.json").read_text())
        summary["scene"]["cloth"]["rows"] = 5
        (self.run / "summary.json").write_text(json.dumps(summary))
        self.only_figures("snapshots")
        self.report(status=2, message=f"{self.run / 'summary.json'}: scene.cloth.rows x cols = 5 x 4, but "
                                      f"{self.run / 'trace.csv'} has 12 particles a frame")
        self.assertNoReportPage()

    def test_a_dummy_csv_without_its_sections(self):
        runfolder.write_csv(self.run / "dummy.csv", "index,x,y,z", [(0, 0.0, 1.0, 0.0)])
        self.only_figures("snapshots")
        self.report(status=2, message=f"{self.run / 'dummy.csv'}: missing column(s) section, point")
        self.assertNoReportPage()


class ValueNoRunWritesTest(ReportTestCase):
    """inf, times out of order, a flag of 7 and unknown statuses were read (exit 0, the metrics
    changed or became nan); refused before anything is written, naming the file, the row and
    the column (docs/analysis.md, Bad input)."""

    def edit_lines(self, name, edit):
        path = self.run / name
        lines = path.read_text().splitlines()
        edit(lines)
        path.write_text("\n".join(lines) + "\n")
        return path

    def test_inf_energy(self):
        path = self.edit_lines("energy.csv", lambda lines: lines.__setitem__(3, lines[3].rsplit(",", 1)[0] + ",inf"))
        self.report(status=2, message=f"{path}: row 3, column total: not a finite number (inf)")
        self.assertNothingWritten()

    def test_trace_time_going_back(self):
        # The second frame (rows 13 to 24 of 12 particles) at t = -1.
        def edit(lines):
            for r in range(13, 25):
                lines[r] = "-1" + lines[r][lines[r].index(","):]
        path = self.edit_lines("trace.csv", edit)
        self.report(status=2, message=f"{path}: row 13, column t: t = -1 is not after the time before it, t = 0")
        self.assertNothingWritten()

    def test_unknown_statuses(self):
        summary = json.loads((self.run / "summary.json").read_text())
        (self.run / "summary.json").write_text(json.dumps({**summary, "status": "banana"}))
        self.report(status=2, message=f"{self.run / 'summary.json'}: status: expected one of ok, diverged, "
                                      'failed, got "banana"')
        results = json.loads((self.directory / "results.json").read_text())
        results["runs"][1]["status"] = "finished"
        (self.directory / "results.json").write_text(json.dumps(results))
        self.report(status=2, message=f"{self.directory / 'results.json'}: runs[1].status: expected one of ok, "
                                      'diverged, failed, error, crashed, got "finished"')
        self.assertNothingWritten()


if __name__ == "__main__":
    unittest.main()
