"""fileio: an input that is not a regular file is refused by name, never waited on; an output
appears whole or not at all."""
import os
import unittest
from pathlib import Path

import runfolder
from drapeanalysis import fileio, runfiles


class OpenInputTest(runfolder.RunFolderTest):
    def setUp(self):
        super().setUp()
        self.folder = self.directory

    def assertRefused(self, path, words, reader=fileio.open_input):
        with self.assertRaises(ValueError) as error:
            reader(path)
        self.assertEqual(str(error.exception), f"{path}: {words}")

    def test_a_regular_file_is_read(self):
        (self.folder / "a.json").write_text('{"a": 1}')
        with fileio.open_input(self.folder / "a.json") as f:
            self.assertEqual(f.read(), '{"a": 1}')
        self.assertEqual(runfiles.read_json(self.folder / "a.json"), {"a": 1})

    def test_a_named_pipe_is_refused_without_waiting_for_a_writer(self):
        pipe = self.folder / "energy.csv"
        os.mkfifo(pipe)
        # Opening a pipe waits for its writer: before this check the readers blocked for ever.
        self.assertRefused(pipe, "not a regular file")
        self.assertRefused(pipe, "not a regular file", runfiles.read_energy)
        self.assertRefused(pipe, "not a regular file", runfiles.read_json)

    def test_a_folder_a_device_and_a_missing_file_are_refused(self):
        self.assertRefused(self.folder, "is a directory, not a file")
        self.assertRefused(Path("/dev/zero"), "not a regular file", runfiles.read_trace)
        self.assertRefused(self.folder / "nope.csv", "no such file", runfiles.read_energy)
        (self.folder / "file").write_text("x")
        self.assertRefused(self.folder / "file" / "summary.json", "Not a directory")

    def test_text_that_is_not_utf8_is_named(self):
        (self.folder / "results.json").write_bytes(b'{"name": "\xff"}')
        with self.assertRaises(ValueError) as error:
            runfiles.read_json(self.folder / "results.json")
        self.assertIn(f"{self.folder / 'results.json'}: not valid JSON", str(error.exception))


class AtomicOutputTest(runfolder.RunFolderTest):
    def setUp(self):
        super().setUp()
        self.folder = self.directory
        self.path = self.folder / "report.html"

    def test_the_file_appears_only_when_complete(self):
        with fileio.atomic_output(self.path) as temporary:
            self.assertEqual(temporary.parent, self.folder)
            self.assertEqual(temporary.suffix, ".html", "writers choose the format by the suffix")
            temporary.write_text("half")
            self.assertFalse(self.path.exists())
            temporary.write_text("whole")
        self.assertEqual(self.path.read_text(), "whole")
        self.assertEqual(os.listdir(self.folder), ["report.html"])

    def test_a_failed_write_keeps_the_old_file_removes_the_temporary_and_names_the_file(self):
        self.path.write_text("old")
        with self.assertRaises(fileio.OutputError) as error:
            with fileio.atomic_output(self.path) as temporary:
                temporary.write_text("half")
                raise OSError(28, "No space left on device")
        self.assertEqual(str(error.exception), f"cannot write {self.path}: No space left on device")
        self.assertEqual(self.path.read_text(), "old")
        self.assertEqual(os.listdir(self.folder), ["report.html"])

    def test_other_errors_pass_through_and_leave_no_temporary(self):
        with self.assertRaises(ValueError):
            with fileio.atomic_output(self.path) as temporary:
                temporary.write_text("half")
                raise ValueError("a malformed input found while drawing")
        self.assertEqual(os.listdir(self.folder), [])

    def test_output_folder(self):
        self.assertTrue(fileio.output_folder(self.folder / "report").is_dir())
        self.assertTrue(fileio.output_folder(self.folder / "report").is_dir(), "there already")
        (self.folder / "file").write_text("x")
        with self.assertRaises(ValueError) as error:
            fileio.output_folder(self.folder / "file")
        self.assertIn(f"{self.folder / 'file'}: not a folder", str(error.exception))
        with self.assertRaises(fileio.OutputError) as error:
            fileio.output_folder(self.folder / "no" / "report")
        self.assertIn(f"cannot create folder {self.folder / 'no' / 'report'}: No such file", str(error.exception))


if __name__ == "__main__":
    unittest.main()
