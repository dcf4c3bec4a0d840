"""report.py's command line (drapeanalysis/report_options.py, docs/analysis.md "Bad input"),
in-process: each number's range, --frames only with --animate, --drapelab a program, and the
runs --animate names checked against the experiment (test_report_bad_input.py runs report.py)."""
import argparse
import contextlib
import io
import unittest
from pathlib import Path

import runfolder
from drapeanalysis import report_options


class OptionTypeTest(unittest.TestCase):
    def test_whole_number_in_range(self):
        frames = report_options.whole_number(2, 10)
        self.assertEqual(frames("2"), 2)
        self.assertEqual(frames("10"), 10)
        for text in ("1", "11", "2.5", "nan", "inf", "", "two"):
            with self.subTest(text), self.assertRaises(argparse.ArgumentTypeError) as error:
                frames(text)
            self.assertEqual(str(error.exception), f"expected a whole number from 2 to 10, got {text!r}")

    def test_folder_path_is_not_empty(self):
        self.assertEqual(report_options.folder_path("out/exp"), Path("out/exp"))
        with self.assertRaises(argparse.ArgumentTypeError) as error:
            report_options.folder_path("")
        self.assertEqual(str(error.exception), "an empty path (give the experiment's folder)")


class ParseTest(unittest.TestCase):
    def refused(self, argv):
        """The error argparse prints, with its exit status 2."""
        stderr = io.StringIO()
        with contextlib.redirect_stderr(stderr), self.assertRaises(SystemExit) as done:
            report_options.parse("report", argv)
        self.assertEqual(done.exception.code, 2)
        return stderr.getvalue()

    def test_defaults(self):
        args = report_options.parse("report", ["exp"])
        self.assertEqual(args.directory, Path("exp"))
        self.assertIsNone(args.animate)
        self.assertEqual(args.frames, report_options.FRAMES_DEFAULT)
        args = report_options.parse("report", ["exp", "--animate", "a", "b", "--frames", "25"])
        self.assertEqual((args.animate, args.frames), (["a", "b"], 25))
        self.assertEqual(report_options.parse("report", ["exp", "--animate"]).animate, [])

    def test_frames_out_of_range_or_without_animate(self):
        low, high = report_options.FRAMES_RANGE
        self.assertIn(f"--frames: expected a whole number from {low} to {high}, got '1'",
                      self.refused(["exp", "--animate", "--frames", "1"]))
        self.assertIn("--frames: only with --animate (it sets the animations' length)",
                      self.refused(["exp", "--frames", "30"]))
        self.assertIn("an empty path (give the experiment's folder)", self.refused([""]))


class DrapelabTest(runfolder.RunFolderTest):
    def test_drapelab_must_be_a_program_this_user_may_run(self):
        program = self.directory / "drapelab"
        program.write_text("#!/bin/sh\n")
        program.chmod(0o644)
        with self.assertRaises(ValueError) as error:
            report_options.check_drapelab(program)
        self.assertEqual(str(error.exception), f"--drapelab {program}: not executable")
        program.chmod(0o755)
        report_options.check_drapelab(program)
        with self.assertRaises(ValueError) as error:
            report_options.check_drapelab(self.directory / "none")
        self.assertTrue(str(error.exception).startswith(f"--drapelab {self.directory / 'none'}: "),
                        str(error.exception))


class AnimatedRunsTest(runfolder.RunFolderTest):
    def setUp(self):
        super().setUp()
        self.rows = runfolder.write_experiment(self.directory, scenes=("scenes/a.json",))

    def assertRefused(self, ids, message):
        with self.assertRaises(ValueError) as error:
            report_options.animated_runs(self.directory, self.rows, ids)
        self.assertEqual(str(error.exception), message)

    def test_no_id_animates_every_traced_run(self):
        self.assertEqual([r["id"] for r in report_options.animated_runs(self.directory, self.rows, [])],
                         ["a-0.001", "a-0.002"])
        self.assertEqual([r["id"] for r in report_options.animated_runs(self.directory, self.rows, ["a-0.002"])],
                         ["a-0.002"])

    def test_an_unknown_or_untraced_run_is_named(self):
        self.assertRefused(["a-0.001", "x", "x", "y"],
                           f"--animate: no run x, y in {self.directory / 'results.json'}")
        (self.directory / "runs" / "a-0.002" / "trace.csv").unlink()
        self.assertRefused(["a-0.002"], "--animate: run a-0.002 has no trace.csv (output.trace_interval = 0) "
                                        "or no summary.json (it did not finish)")
        (self.directory / "runs" / "a-0.001" / "summary.json").unlink()
        self.assertRefused([], "--animate: no run has a trace.csv (output.trace_interval = 0)")


if __name__ == "__main__":
    unittest.main()
