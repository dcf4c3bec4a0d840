"""event_trace/ (docs/outputs.md): frames at a fixed fine rate after each event, read back with
numpy and the analysis reader, checked against trace.csv and against the steps they must not
change.

Run by ctest as `event_trace` with the drapelab executable as its argument: combination 1 (a
hold at about 0.43 s, a release at 1.5 s) for 2 s with leap-frog at 0.5 ms, a trace every 10 ms
and an event trace every 2 ms for 0.1 s after each event.
"""
import os
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[3] / "analysis"))
from drapeanalysis import runfiles  # noqa: E402

DRAPELAB = os.environ.get("DRAPELAB_EXE", "build/bin/drapelab")
SOURCE_DIR = os.environ.get("DRAPE_SOURCE_DIR", ".")
INTERVAL, WINDOW = 0.002, 0.1


class EventTrace(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        scene = os.path.join(SOURCE_DIR, "experiments", "scenes", "combination1_hold_release.json")
        common = ["--quiet", "--overwrite", "--set", "duration=2.0", "--set", "integrator.dt=0.0005",
                  "--set", "output.trace_interval=0.01"]
        cls.out = Path(cls.tmp.name) / "with"
        cls.plain = Path(cls.tmp.name) / "without"
        subprocess.run([DRAPELAB, "run", scene, "--out", str(cls.out), *common,
                        "--set", f"output.event_trace_interval={INTERVAL}",
                        "--set", f"output.event_trace_window={WINDOW}"], check=True)
        subprocess.run([DRAPELAB, "run", scene, "--out", str(cls.plain), *common], check=True)
        cls.summary = runfiles.read_summary(cls.out)
        cls.fine = runfiles.read_event_trace(cls.out)
        cls.coarse = runfiles.trace_frames(runfiles.read_trace(cls.out / "trace.csv"))

    def test_windows_start_at_the_start_and_at_each_event_at_the_fixed_rate(self):
        t = self.fine["t"]
        starts = [0.0] + [e["t"] for e in self.summary["events"]]
        self.assertEqual(len(starts), 3)  # the start, the hold and the release
        frames_per_window = round(WINDOW / INTERVAL) + 1
        self.assertEqual(len(t), len(starts) * frames_per_window)
        for k, start in enumerate(starts):
            window = t[k * frames_per_window:(k + 1) * frames_per_window]
            np.testing.assert_allclose(window, start + INTERVAL * np.arange(frames_per_window),
                                       rtol=0, atol=1e-12)
        np.testing.assert_array_equal(np.nonzero(self.fine["event"])[0],
                                      frames_per_window * np.arange(len(starts)))

    def test_shapes_and_types(self):
        n = self.summary["particles"]
        k = len(self.fine["t"])
        self.assertEqual(self.fine["x"].shape, (k, n, 3))
        self.assertEqual(self.fine["v"].shape, (k, n, 3))
        self.assertEqual(self.fine["fixed"].shape, (k, n))
        self.assertEqual(np.load(self.out / "event_trace" / "x.npy").dtype, np.float32)

    def test_frames_at_common_times_match_the_trace(self):
        # Both are written from the same step ends and interpolants; x.npy is single precision.
        common = 0
        for i, t in enumerate(self.fine["t"]):
            match = np.nonzero(np.abs(self.coarse["t"] - t) < 1e-12)[0]
            if len(match) == 0:
                continue
            j = match[-1]
            common += 1
            np.testing.assert_allclose(self.fine["x"][i], self.coarse["x"][j], rtol=0, atol=1e-6)
            np.testing.assert_array_equal(self.fine["fixed"][i], self.coarse["fixed"][j])
            np.testing.assert_array_equal(self.fine["contact"][i], self.coarse["contact"][j])
        # The windows at 0 s and at the release (1.5 s) share every 10 ms frame with the trace;
        # the hold's (at about 0.4294 s) only its first frame.
        self.assertEqual(common, 2 * (round(WINDOW / 0.01) + 1) + 1)

    def test_the_held_particle_is_fixed_after_the_hold(self):
        hold = next(e for e in self.summary["events"] if e["type"] == "hold")
        after = self.fine["t"] >= hold["t"]
        release = next(e for e in self.summary["events"] if e["type"] == "release")
        held = after & (self.fine["t"] < release["t"])
        self.assertTrue(self.fine["fixed"][held, hold["particle"]].all())

    def test_recording_does_not_change_the_steps(self):
        self.assertEqual((self.out / "state.csv").read_bytes(), (self.plain / "state.csv").read_bytes())
        self.assertEqual((self.out / "energy.csv").read_bytes(), (self.plain / "energy.csv").read_bytes())


if __name__ == "__main__":
    if len(sys.argv) > 1:
        DRAPELAB = sys.argv.pop(1)
    unittest.main()
