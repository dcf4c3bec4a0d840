"""A run's energy.csv, hands.csv and trace.csv must reach its sim_time (run_series): a file cut on
a row's end parses, and only summary.json tells that it stops early."""
import unittest

import numpy as np

import runfolder
from drapeanalysis import runfiles
from drapeanalysis.run_series import read_run_series


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
