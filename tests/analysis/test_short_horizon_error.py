"""The error against the reference over one Kinect frame (docs/analysis.md, "Error against a
reference"), from two runs' event traces with a known, linearly growing difference."""
import math

import numpy as np

import runfolder
from drapeanalysis import metrics
from runfolder import RunFolderTest

RATE = 1000.0  # event-trace frames a second
DRIFT = 0.01   # m/s: particle 0 of the reference moves away at this speed; particle 1 agrees


def frames(window_starts, end):
    """Event-trace times: from each window start to the next (or `end`) at RATE."""
    bounds = list(window_starts) + [end]
    return np.concatenate([t0 + np.arange(round((t1 - t0) * RATE)) / RATE
                           for t0, t1 in zip(bounds[:-1], bounds[1:])] + [[end]])


class ShortHorizonErrorTest(RunFolderTest):
    def write(self, name, events, offset):
        run = self.make_run(name)
        runfolder.write_summary(run, events, runfolder.CLOTH_SCENE, sim_time=0.7)
        t = frames([0.0] + [e["t"] for e in events], 0.7)
        x = np.zeros((len(t), 2, 3))
        x[:, 0, 0] = offset * t
        runfolder.write_event_trace(run, t, x)
        return run

    def test_error_one_frame_after_the_start_and_the_shared_events(self):
        hold = {"t": 0.2, "type": "hold", "hand": "left"}
        # The run's attach is fixed at 0.35 s, the reference's at another time: not shared.
        run = self.write("a", [hold, {"t": 0.35, "type": "attach_fixed"}], 0.0)
        reference = self.write("ref", [hold, {"t": 0.4, "type": "attach_fixed"}], DRIFT)
        out = metrics.short_horizon_error(run, reference)

        # e(t) = sqrt((DRIFT t)^2 / 2) over two particles, at the 1 kHz frame nearest t + 1/30 s.
        def e(t):
            return DRIFT * t / math.sqrt(2.0)

        self.assertClose(out["short_error_start"], e(0.033), rel=1e-6)
        self.assertClose(out["short_error_events_inherited"], e(0.2), rel=1e-6)
        self.assertClose(out["short_error_events"], e(0.233), rel=1e-6)
        self.assertEqual(out["short_error_events_n"], 1)

    def test_events_at_the_same_instant_up_to_round_off_are_shared(self):
        # A 2e-5 s reference reaches a key at 1.5 s as 1.4999999999977245 s (its steps' sum).
        run = self.write("a", [{"t": 0.2, "type": "release", "hand": "left"}], 0.0)
        reference = self.write("ref", [{"t": 0.2 - 2.3e-12, "type": "release", "hand": "left"}],
                               DRIFT)
        out = metrics.short_horizon_error(run, reference)
        self.assertEqual(out["short_error_events_n"], 1)
        self.assertClose(out["short_error_events"], DRIFT * 0.233 / math.sqrt(2.0), rel=1e-6)

    def test_identical_runs_have_no_error_and_missing_traces_give_nothing(self):
        hold = [{"t": 0.2, "type": "hold", "hand": "left"}]
        run, reference = self.write("a", hold, DRIFT), self.write("ref", hold, DRIFT)
        out = metrics.short_horizon_error(run, reference)
        self.assertEqual(out["short_error_start"], 0.0)
        self.assertEqual(out["short_error_events"], 0.0)
        bare = self.make_run("bare")
        runfolder.write_summary(bare, hold, runfolder.CLOTH_SCENE)
        self.assertEqual(metrics.short_horizon_error(run, bare), {})

    def test_a_reference_with_other_particles_names_both_traces(self):
        hold = [{"t": 0.2, "type": "hold", "hand": "left"}]
        run = self.write("a", hold, 0.0)
        other = self.make_run("ref")
        runfolder.write_summary(other, hold, runfolder.CLOTH_SCENE, sim_time=0.7)
        t = frames([0.0, 0.2], 0.7)
        runfolder.write_event_trace(other, t, np.zeros((len(t), 3, 3)))
        with self.assertRaisesRegex(ValueError, r"a/event_trace: 2 particles, the reference .*ref/event_trace has 3"):
            metrics.short_horizon_error(run, other)

    def test_close_events_both_count(self):
        # The release 0.01 s after the hold: 1/30 s after the hold falls in the release's window.
        events = [{"t": 0.2, "type": "hold", "hand": "left"}, {"t": 0.21, "type": "release"}]
        out = metrics.short_horizon_error(self.write("a", events, 0.0),
                                          self.write("ref", events, DRIFT))
        e = DRIFT / math.sqrt(2.0)
        self.assertEqual(out["short_error_events_n"], 2)
        self.assertClose(out["short_error_events_inherited"], e * (0.2 + 0.21) / 2, rel=1e-6)
        self.assertClose(out["short_error_events"], e * (0.233 + 0.243) / 2, rel=1e-6)

    def test_no_frame_one_horizon_later_gives_no_value(self):
        # Windows of 0.02 s (output.event_trace_window below 1/30 s): no frame at t + 1/30 s.
        runs = []
        for name, offset in (("a", 0.0), ("ref", DRIFT)):
            run = self.make_run(name)
            scene = {**runfolder.CLOTH_SCENE, "output": {"event_trace_interval": 1 / RATE,
                                                         "event_trace_window": 0.02}}
            runfolder.write_summary(run, [{"t": 0.2, "type": "hold", "hand": "left"}], scene,
                                    sim_time=1.0)
            t = np.concatenate([np.arange(21) / RATE, 0.2 + np.arange(21) / RATE])
            x = np.zeros((len(t), 2, 3))
            x[:, 0, 0] = offset * t
            runfolder.write_event_trace(run, t, x)
            runs.append(run)
        out = metrics.short_horizon_error(*runs)
        self.assertTrue(math.isnan(out["short_error_start"]))
        self.assertTrue(math.isnan(out["short_error_events"]))
        self.assertEqual(out["short_error_events_n"], 0)


if __name__ == "__main__":
    import unittest
    unittest.main()
