"""A run's energy.csv, hands.csv and trace.csv must reach its sim_time, event_trace/ the end of
its last event's window, and restart_error.csv must have the rows summary.json counts
(run_series): a file cut on a row's end parses, and only summary.json tells that it stops early."""
import unittest

import numpy as np

import runfolder
from drapeanalysis import runfiles
from drapeanalysis.run_series import read_run_event_trace, read_run_restart_error, read_run_series


class RunSeriesEndTest(runfolder.RunFolderTest):
    def setUp(self):
        super().setUp()
        self.run = self.make_run()

    def summary(self, sim_time, **scene_output):
        runfolder.write_summary(self.run, scene={"output": scene_output}, status="diverged",
                                sim_time=sim_time, step_max=0.025)
        return runfiles.read_summary(self.run)

    def assertCut(self, name, summary, *words):
        with self.assertRaises(ValueError) as error:
            read_run_series(self.run, summary, name)
        text = str(error.exception)
        for word in (str(self.run / name), "the file is cut") + words:
            self.assertIn(word, text)

    def test_energy_rows_may_lag_by_an_interval_and_a_step(self):
        runfolder.write_energy(self.run, [0.0, 0.1, 0.2], [-1.0, -1.0, -1.0])
        # 0.2 + 0.1 + 0.025 = 0.325: a diverged run's last row may lag that much, no more.
        summary = self.summary(0.32, energy_interval=0.1)
        self.assertEqual(list(read_run_series(self.run, summary, "energy.csv")["t"]), [0.0, 0.1, 0.2])
        self.assertCut("energy.csv", self.summary(0.33, energy_interval=0.1), "the rows end at t = 0.2 s",
                       "sim_time = 0.33 s", "output.energy_interval = 0.1 s", "a step of 0.025 s")

    def test_hands_run_on_the_energy_clock(self):
        # hands.csv is written at energy.csv's times, so its slack is the energy interval.
        runfolder.write_hands(self.run, [(t, hand, 1, 0.0, 1.0, 0.5) for t in (0.0, 0.01, 0.02)
                                         for hand in ("left", "right")])
        self.assertEqual(len(read_run_series(self.run, self.summary(0.05), "hands.csv")), 6)
        self.assertCut("hands.csv", self.summary(0.06), "the rows end at t = 0.02 s",
                       "output.energy_interval = 0.01 s")
        summary = self.summary(0.3, energy_interval=0.5)
        self.assertEqual(len(read_run_series(self.run, summary, "hands.csv")), 6)

    def test_trace_frames_on_the_trace_clock(self):
        x = np.zeros((3, 2, 3))
        runfolder.write_trace(self.run, [0.0, 0.1, 0.2], x)
        summary = self.summary(0.32, trace_interval=0.1)
        self.assertEqual(len(read_run_series(self.run, summary, "trace.csv")), 6)
        self.assertCut("trace.csv", self.summary(0.4, trace_interval=0.1), "the rows end at t = 0.2 s",
                       "output.trace_interval = 0.1 s")

    def test_the_event_trace_reaches_its_last_window_end(self):
        # Events at 0.1 and 0.2 s, windows of 0.05 s sampled every 0.01 s: the last window ends at
        # 0.25 s. Cut after 0.15 s (every array cut alike) it is refused.
        events = [{"type": "hold", "t": 0.1}, {"type": "release", "t": 0.2}]
        t = np.concatenate([np.arange(0.0, 0.051, 0.01), np.arange(0.1, 0.151, 0.01), np.arange(0.2, 0.251, 0.01)])
        output = {"event_trace_interval": 0.01, "event_trace_window": 0.05}
        runfolder.write_summary(self.run, events, scene={"output": output}, sim_time=1.0, step_max=0.001)
        runfolder.write_event_trace(self.run, t[:12], np.zeros((12, 2, 3)))
        with self.assertRaises(ValueError) as error:
            read_run_event_trace(self.run, runfiles.read_summary(self.run))
        self.assertEqual(str(error.exception),
                         f"{self.run / 'event_trace' / 't.npy'}: the frames end at t = 0.15 s, before the last "
                         "event's window end = 0.25 s in summary.json (more than output.event_trace_interval = "
                         "0.01 s and a step of 0.001 s): the file is cut")
        (self.run / "event_trace").rename(self.run / "cut")
        runfolder.write_event_trace(self.run, t, np.zeros((len(t), 2, 3)))
        self.assertEqual(len(read_run_event_trace(self.run, runfiles.read_summary(self.run))["t"]), len(t))
        # A run that stopped at 0.22 s: its last window ends there.
        runfolder.write_summary(self.run, events, scene={"output": output}, status="diverged",
                                sim_time=0.22, step_max=0.001)
        (self.run / "event_trace").rename(self.run / "whole")
        runfolder.write_event_trace(self.run, t[:15], np.zeros((15, 2, 3)))
        self.assertEqual(len(read_run_event_trace(self.run, runfiles.read_summary(self.run))["t"]), 15)

    def test_an_ignored_key_opens_no_window(self):
        # A release key with nothing held at 0.3 s is ignored: the recorder opens no window there,
        # so frames to 0.25 s are the whole trace (a run whose hand never held, as a seed can).
        events = [{"type": "hold", "t": 0.1}, {"type": "release", "t": 0.2}, {"type": "ignored", "t": 0.3}]
        t = np.concatenate([np.arange(0.0, 0.051, 0.01), np.arange(0.1, 0.151, 0.01), np.arange(0.2, 0.251, 0.01)])
        output = {"event_trace_interval": 0.01, "event_trace_window": 0.05}
        runfolder.write_summary(self.run, events, scene={"output": output}, sim_time=1.0, step_max=0.001)
        runfolder.write_event_trace(self.run, t, np.zeros((len(t), 2, 3)))
        self.assertEqual(len(read_run_event_trace(self.run, runfiles.read_summary(self.run))["t"]), len(t))
        events[2]["type"] = "hold"  # a real event there would need its window
        runfolder.write_summary(self.run, events, scene={"output": output}, sim_time=1.0, step_max=0.001)
        with self.assertRaises(ValueError):
            read_run_event_trace(self.run, runfiles.read_summary(self.run))

    def test_restart_error_has_the_rows_the_summary_counts(self):
        header = "t,events,horizon,status,error_rms,error_max,reference_motion_rms"
        rows = [(0.0, "start", 0.01, "ok", 1e-6, 2e-6, 1e-3), (0.1, "hold", 0.01, "ok", 2e-6, 3e-6, 1e-3)]
        runfolder.write_csv(self.run / "restart_error.csv", header, rows)
        runfolder.write_summary(self.run, sim_time=1.0, restart_error={"rows": 2})
        self.assertEqual(len(read_run_restart_error(self.run, runfiles.read_summary(self.run))), 2)
        runfolder.write_summary(self.run, sim_time=1.0, restart_error={"rows": 3})
        with self.assertRaises(ValueError) as error:
            read_run_restart_error(self.run, runfiles.read_summary(self.run))
        self.assertEqual(str(error.exception), f"{self.run / 'restart_error.csv'}: 2 rows, but summary.json's "
                         "restart_error.rows is 3: the file is cut or was changed")
        runfolder.write_summary(self.run, sim_time=1.0, restart_error=2)
        with self.assertRaises(ValueError) as error:
            read_run_restart_error(self.run)  # its summary read from the folder
        self.assertEqual(str(error.exception), f"{self.run / 'summary.json'}: restart_error: expected an "
                         "object, got 2")
        # An ok branch measured its error: nan there is damage (it blanked the metric silently).
        runfolder.write_csv(self.run / "restart_error.csv", header, [rows[0][:4] + ("nan",) + rows[0][5:]])
        with self.assertRaises(ValueError) as error:
            runfiles.read_restart_error(self.run / "restart_error.csv")
        self.assertEqual(str(error.exception), f"{self.run / 'restart_error.csv'}: row 1, column error_rms: "
                         "not a finite number in a branch whose status is ok")

    def test_summary_numbers_the_check_reads(self):
        runfolder.write_energy(self.run, [0.0, 0.1], [-1.0, -1.0])
        for summary, message in (({}, "no sim_time"),
                                 ({"sim_time": None}, "sim_time: expected a finite number, got null"),
                                 ({"sim_time": 0.1, "step_max": "x"}, 'step_max: expected a finite number, got "x"'),
                                 ({"sim_time": 0.1, "scene": {"output": {"energy_interval": []}}},
                                  "scene.output.energy_interval: expected a finite number, got []")):
            with self.subTest(message), self.assertRaises(ValueError) as error:
                read_run_series(self.run, summary, "energy.csv")
            self.assertEqual(str(error.exception), f"{self.run / 'summary.json'}: {message}")


if __name__ == "__main__":
    unittest.main()
