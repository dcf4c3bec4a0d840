"""plot_state.py (front and side views of a run's state.csv, docs/viewer.md): the picture
written beside the run's files and named on stdout, and a file without rows named."""
import subprocess
import sys
import unittest

import numpy as np
from PIL import Image

import runfolder

SCRIPT = runfolder.ANALYSIS_DIR / "plot_state.py"


class PlotStateTest(runfolder.RunFolderTest):
    def plot(self, *args):
        return subprocess.run([sys.executable, str(SCRIPT), *map(str, args)], capture_output=True,
                              text=True, timeout=120)

    def test_the_picture_is_written_beside_the_state(self):
        run = self.make_run()
        x = np.array([[0.0, 1.0, 0.0], [0.1, 1.0, 0.0], [0.0, 0.9, 0.05], [0.1, 0.9, 0.05]])
        runfolder.write_state(run, x, cols=2, fixed=np.array([1, 1, 0, 0]))
        done = self.plot(run)
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertEqual(done.stdout.strip(), str(run / "state.png"), "beside state.csv unless --out")
        with Image.open(run / "state.png") as image:
            width, height = image.size
        self.assertGreater(width, height, "two views side by side")

    def test_a_state_without_rows_is_named(self):
        run = self.make_run()
        (run / "state.csv").write_text(runfolder.STATE_HEADER + "\n")
        done = self.plot(run)
        self.assertEqual(done.returncode, 1)
        self.assertEqual(done.stderr.strip(), f"{run / 'state.csv'}: no rows")


if __name__ == "__main__":
    unittest.main()
