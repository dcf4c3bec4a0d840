"""fileio: an input that is not a regular file is refused by name, never waited on."""
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


if __name__ == "__main__":
    unittest.main()
