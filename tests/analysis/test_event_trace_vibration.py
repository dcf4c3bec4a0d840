"""The vibration after events from event_trace/ (docs/outputs.md, docs/analysis.md): the fine
fixed-rate frames are used when a run wrote them, and a broken file is named."""
import math

import numpy as np

import runfolder
from drapeanalysis import metrics, runfiles
from runfolder import RunFolderTest


class EventTraceVibrationTest(RunFolderTest):
    def test_event_windows_come_from_the_event_trace(self):
        # A 200 Hz vibration of amplitude A after a hold at 0.2 s: sampled at 100 Hz (trace.csv)
        # it is a constant and reads 0; event_trace/ at 1 kHz sees it, and the event window must
        # read A / sqrt(2) from it.
        run = self.make_run()
        runfolder.write_summary(run, [{"t": 0.2, "type": "hold", "hand": "left"}], runfolder.CLOTH_SCENE,
                                sim_time=1.0)
        amplitude, f = 1e-3, 200.0
        d = runfolder.unit_directions(1)

        def motion(t):
            return (amplitude * np.sin(2 * np.pi * f * (t - 0.2)))[:, None, None] * d[None]

        coarse = np.arange(101) / 100.0
        runfolder.write_trace(run, coarse, motion(coarse))
        fine = 0.2 + np.arange(501) / 1000.0
        runfolder.write_event_trace(run, fine, motion(fine))
        out, windows = metrics.vibration(run, runfiles.read_json(run / "summary.json"))
        self.assertClose(windows[0]["vibration_rms"], amplitude / math.sqrt(2), rel=0.01)
        self.assertClose(out["vibration_sample_hz_events"], 1000.0, rel=1e-12)
        # The last window still comes from trace.csv, where the 200 Hz motion is a constant.
        self.assertLess(out["vibration_rms_final"], 1e-9)

    def test_a_truncated_event_trace_names_its_file(self):
        run = self.make_run()
        runfolder.write_summary(run, [], runfolder.CLOTH_SCENE)
        folder = run / "event_trace"
        folder.mkdir()
        np.save(folder / "t.npy", np.arange(3) / 1000.0)
        for name in ("x", "v"):
            np.save(folder / f"{name}.npy", np.zeros((2, 1, 3), np.float32))
        np.save(folder / "fixed.npy", np.zeros((3, 1), np.uint8))
        (folder / "contact.npy").write_bytes(b"not numpy")
        with self.assertRaisesRegex(ValueError, "contact.npy"):
            runfiles.read_event_trace(run)
        np.save(folder / "contact.npy", -np.ones((3, 1), np.int32))
        with self.assertRaisesRegex(ValueError, "x.npy: 2 frames, t.npy has 3"):
            runfiles.read_event_trace(run)


if __name__ == "__main__":
    import unittest
    unittest.main()
