"""The energy and vibration metrics of docs/analysis.md against closed forms, on small synthetic
run folders (the mapping and reference errors: test_error_metrics.py)."""
import math
import unittest

import numpy as np
import pandas as pd

import runfolder
from drapeanalysis import metrics, runfiles


def drift(t, total):
    return metrics.energy_drift({"t": np.asarray(t, float), "total": np.asarray(total, float)})


class EnergyDriftTest(runfolder.RunFolderTest):
    T = 10.0
    t = np.linspace(0.0, 10.0, 1001)

    def test_linear_drift(self):
        # E = E0 (1 + a t): r(t) = |a| t, relative to |E0| (E0 < 0 as with gravity below y = 0).
        e0, a = -4.0, 0.02
        out = drift(self.t, e0 * (1 + a * self.t))
        self.assertClose(out["energy_drift_max_rel"], a * self.T)
        self.assertClose(out["energy_drift_final_rel"], a * self.T)
        self.assertClose(out["energy_drift_rate"], a)
        self.assertClose(out["energy_drift_exponent"], 1.0)

    def test_quadratic_growth(self):
        # r = b t^2: envelope exponent 2; the least-squares slope of t^2 on an even grid over
        # [0, T] is exactly T, so the rate is b T.
        e0, b = 3.0, 1e-4
        out = drift(self.t, e0 * (1 - b * self.t**2))
        self.assertClose(out["energy_drift_max_rel"], b * self.T**2)
        self.assertClose(out["energy_drift_rate"], b * self.T)
        self.assertClose(out["energy_drift_exponent"], 2.0)

    def test_bounded_oscillation(self):
        # A symplectic method's error: oscillating, never growing. Exponent and rate near 0.
        e0, eps, period = 2.5, 1e-5, 0.37
        out = drift(self.t, e0 * (1 + eps * np.sin(2 * np.pi * self.t / period)))
        self.assertClose(out["energy_drift_max_rel"], eps, rel=1e-3)
        self.assertLess(abs(out["energy_drift_exponent"]), 1e-3)
        self.assertLess(abs(out["energy_drift_rate"]) * self.T, 0.02 * eps)

    def test_max_and_final_differ(self):
        # Energy that goes away and comes back: max c at T/2, final error 0.
        e0, c = 1.0, 0.05
        out = drift(self.t, e0 * (1 + c * np.sin(np.pi * self.t / self.T)))
        self.assertClose(out["energy_drift_max_rel"], c)
        self.assertLess(out["energy_drift_final_rel"], 1e-14)

    def test_exact_conservation_and_short_series(self):
        out = drift(self.t, np.full_like(self.t, 7.0))
        self.assertEqual(out["energy_drift_max_rel"], 0.0)
        self.assertEqual(out["energy_drift_rate"], 0.0)
        self.assertTrue(math.isnan(out["energy_drift_exponent"]), "log of a zero envelope")
        out = drift([0.0, 0.1], [1.0, 1.1])
        self.assertClose(out["energy_drift_max_rel"], 0.1)
        self.assertTrue(math.isnan(out["energy_drift_rate"]))
        self.assertTrue(math.isnan(out["energy_drift_exponent"]))

    def test_from_energy_csv(self):
        run = self.make_run()
        runfolder.write_summary(run, sim_time=float(self.t[-1]))
        e0, a = -4.0, 0.02
        runfolder.write_energy(run, self.t, e0 * (1 + a * self.t))
        out, windows = metrics.run_metrics(self.directory, self.row(), {})
        self.assertClose(out["energy_drift_max_rel"], a * self.T)
        self.assertClose(out["energy_drift_rate"], a)
        self.assertClose(out["energy_drift_exponent"], 1.0)
        self.assertEqual(windows, [])
        self.assertNotIn("vibration_rms_final", out, "no trace.csv, no vibration")

    def test_attaches_never_fixed_are_counted(self):
        attach, fixed = {"type": "attach", "t": 0.2}, {"type": "attach_fixed", "t": 0.25}
        self.assertEqual(metrics.attach_unfixed({"events": [attach, fixed, dict(attach, t=0.9)]}),
                         {"attach_unfixed_count": 1})
        self.assertEqual(metrics.attach_unfixed({"events": [attach, fixed]}), {"attach_unfixed_count": 0})
        self.assertEqual(metrics.attach_unfixed({"events": [{"type": "hold", "t": 0.1}]}), {})

    def test_a_diverged_run_has_no_drift(self):
        # Diverged at the first step: its one energy row reads a drift of 0, and drapelab's own
        # summary columns too; all of them are emptied, as the run is not comparable.
        run = self.make_run()
        runfolder.write_summary(run, status="diverged", sim_time=0.006, step_max=0.002)
        runfolder.write_energy(run, [0.0], [-4.0])
        out, _ = metrics.run_metrics(self.directory, self.row(), {})
        for column in ("energy_drift_max_rel", "energy_drift_final_rel", "energy_drift_rate",
                       "energy_drift_exponent") + metrics.SUMMARY_DRIFT:
            self.assertTrue(math.isnan(out[column]), column)


class VibrationWindowTest(runfolder.RunFolderTest):
    # The spectral split (test_spectral.py) reads a sinusoid 10 times above the cutoff within
    # 0.5 % (the window's ends): the tolerance of the high-frequency RMS below.
    # Trace every 1 ms from 0.8 s to 1.7 s; the window is [1.0, 1.5]; cutoff 20 Hz.
    t = np.arange(800, 1701) / 1000.0
    t0, t1 = 1.0, 1.5
    cutoff = 20.0

    def slow_motion(self, n):
        """Draping-like motion: a drift plus a 3 s swing, and its velocity."""
        t = self.t[:, None, None]
        start = np.arange(n)[None, :, None] * np.array([0.1, 0.0, 0.05])
        u = np.array([0.2, -0.3, 0.1])
        swing = np.array([0.0, 0.02, 0.0])
        w = 2 * np.pi / 3.0
        return start + u * t + swing * np.sin(w * t), u + swing * w * np.cos(w * t) + 0 * start

    def test_sinusoid_on_slow_motion(self):
        # x_i = slow_i(t) + A sin(2 pi f t + phi_i) d_i: the high-frequency residual is the
        # sinusoid, RMS A / sqrt 2; velocity RMS 2 pi f A / sqrt 2.
        n, amplitude, f = 4, 1e-3, 200.0
        x, v = self.slow_motion(n + 1)
        phase = 2 * np.pi * f * self.t[:, None] + 0.7 * np.arange(n + 1)
        d = runfolder.unit_directions(n + 1)
        inside = ((self.t >= self.t0) & (self.t <= self.t1))[:, None, None]
        scale = np.where(inside, amplitude, 10 * amplitude)  # outside the window: ignored
        x = x + scale * np.sin(phase)[:, :, None] * d
        v = v + scale * 2 * np.pi * f * np.cos(phase)[:, :, None] * d
        # The last particle is fixed for one frame in the window and shakes hard: not free.
        fixed = np.zeros(x.shape[:2], bool)
        fixed[300, n] = True
        x[:, n] += 0.05 * np.sin(2 * np.pi * 90 * self.t)[:, None]
        out = metrics.vibration_window(runfolder.trace_dict(self.t, x, v, fixed), self.t0, self.t1, self.cutoff)
        self.assertEqual(out["frames"], 501)
        self.assertClose(out["vibration_rms"], amplitude / math.sqrt(2), rel=0.005)
        self.assertClose(out["vibration_velocity_rms"], 2 * np.pi * f * amplitude / math.sqrt(2), rel=0.005)
        self.assertTrue(math.isnan(out["hand_jitter_rms"]), "no hands.csv")

    def test_uniform_motion_drops_out(self):
        # Motion linear in time (positions drifting, velocities growing as in free fall) has no
        # high-frequency part: the detrending polynomial holds it exactly.
        n = 3
        t = self.t[:, None, None]
        x = np.arange(n)[None, :, None] * 0.1 + np.array([0.3, -0.5, 0.2]) * t
        v = np.array([0.3, -0.5, 0.2]) + np.array([0.0, -9.81, 0.0]) * t + 0 * x
        out = metrics.vibration_window(runfolder.trace_dict(self.t, x, v), self.t0, self.t1, self.cutoff)
        self.assertLess(out["vibration_rms"], 1e-12)
        self.assertLess(out["vibration_velocity_rms"], 1e-10)

    def speeds_trace(self, speed):
        """A trace whose particles all move at `speed(t)` (the RMS speed), in different directions."""
        n = 3
        v = speed(self.t)[:, None, None] * runfolder.unit_directions(n)[None]
        return runfolder.trace_dict(self.t, np.zeros_like(v), v)

    def test_settle_time_of_exponential_decay(self):
        # s(t) = s0 exp(-(t - t0) / tau) falls below 0.01 m/s at tau ln(s0 / 0.01); the settle
        # time is that of the first frame at or after it (frames every 1 ms).
        s0, tau = 0.5, 0.05
        trace = self.speeds_trace(lambda t: np.where(t < self.t0, 2.0, s0 * np.exp(-(t - self.t0) / tau)))
        expected = tau * math.log(s0 / metrics.SETTLE_SPEED)
        settle = metrics.vibration_window(trace, self.t0, self.t1, self.cutoff)["settle_time"]
        self.assertGreaterEqual(settle, expected - 1e-12)
        self.assertLessEqual(settle, expected + 1e-3 + 1e-12)

    def test_settle_time_waits_for_the_last_excursion(self):
        # Below the limit from 1.2 s, back above over [1.35, 1.36]: settled from the next frame.
        trace = self.speeds_trace(lambda t: np.where((t < 1.2) | ((t >= 1.35) & (t <= 1.36)), 0.02, 0.001))
        self.assertClose(metrics.vibration_window(trace, self.t0, self.t1, self.cutoff)["settle_time"], 0.361)
        never = metrics.vibration_window(self.speeds_trace(lambda t: 0.02 + 0 * t), self.t0, self.t1, self.cutoff)
        self.assertTrue(math.isnan(never["settle_time"]))
        at_rest = metrics.vibration_window(self.speeds_trace(lambda t: 0.001 + 0 * t), self.t0, self.t1, self.cutoff)
        self.assertEqual(at_rest["settle_time"], 0.0)

    def test_contact_switch_rate(self):
        # Frames every 0.1 s over 1 s: particle 0 switches 3 times, particle 1 never; particle 2
        # is fixed in one frame and switches every frame (not counted). 3 / (2 particles x 1 s).
        t = np.arange(11) / 10.0
        contact = np.empty((11, 3), int)
        contact[:, 0] = [-1, -1, 5, 5, 6, 6, 6, -1, -1, -1, -1]
        contact[:, 1] = 7
        contact[:, 2] = np.arange(11)
        fixed = np.zeros((11, 3), bool)
        fixed[4, 2] = True
        trace = runfolder.trace_dict(t, np.zeros((11, 3, 3)), fixed=fixed, contact=contact)
        self.assertClose(metrics.vibration_window(trace, 0.0, 1.0, 2.0)["contact_switch_rate"], 1.5)

    def test_too_few_frames_or_no_free_particle(self):
        trace = runfolder.trace_dict(self.t, np.zeros((len(self.t), 2, 3)))
        self.assertNotIn("vibration_rms", metrics.vibration_window(trace, 1.0, 1.001, self.cutoff))
        trace["fixed"][:] = True
        self.assertNotIn("vibration_rms", metrics.vibration_window(trace, self.t0, self.t1, self.cutoff))


class RunVibrationTest(runfolder.RunFolderTest):
    """vibration() over a run: event windows, final window, steady holding, hands, settling."""

    def test_windows_of_a_run_with_events(self):
        run = self.make_run()
        events = [{"t": 0.2, "type": "hold", "hand": "left"},
                  {"t": 1.0, "type": "ignored", "reason": "no candidate"},
                  {"t": 2.0, "type": "release", "hand": "left"}]
        runfolder.write_summary(run, events, runfolder.CLOTH_SCENE, sim_time=3.0)
        # Frames every 1 ms to 3 s; those at the hold and the release are event frames (one frame
        # a time: experiments/output/frame_recorder.cpp).
        step = np.arange(3001) / 1000.0
        t = step
        event = np.zeros(len(t), int)
        event[np.searchsorted(t, [0.2, 2.0])] = 1
        # Vibration amplitude per phase: after the hold 1e-3, steady holding (from 0.7 s) 2e-3,
        # after the release 0.6e-3, over the last 0.5 s 0.3e-3.
        amplitude = np.select([t < 0.7, t < 2.0, t < 2.5], [1e-3, 2e-3, 0.6e-3], 0.3e-3)
        n, f = 2, 250.0
        d = runfolder.unit_directions(n)
        phase = 2 * np.pi * f * t[:, None] + np.arange(n)
        x = 0.05 * t[:, None, None] + (amplitude[:, None] * np.sin(phase))[:, :, None] * d
        # Speeds: falling at 0.3 m/s, then decaying after each event (tau 0.02 s, then 0.05 s).
        speed = np.select([t < 0.2, t < 2.0], [0.3, 0.5 * np.exp(-(t - 0.2) / 0.02)],
                          0.5 * np.exp(-(t - 2.0) / 0.05))
        v = speed[:, None, None] * d[None]
        runfolder.write_trace(run, t, x, v, event=event)
        # The left hand jitters (amplitude J at 250 Hz on a slow drift); the right one is not
        # tracked and its (meaningless) position must not count.
        jitter = 4e-4
        hands = []
        for ti in step:
            hands.append((ti, "left", 1, 0.1 + 0.02 * ti + jitter * math.sin(2 * math.pi * 250 * ti), 1.2, 0.3))
            hands.append((ti, "right", 0, 50 * math.sin(2 * math.pi * 90 * ti), 0.0, 0.0))
        runfolder.write_hands(run, hands)

        out, windows = metrics.vibration(run, runfiles.read_json(run / "summary.json"))
        self.assertEqual([(w["window_start"], w["window_end"]) for w in windows], [(0.2, 0.7), (2.0, 2.5)])
        root2 = math.sqrt(2)
        self.assertClose(windows[0]["vibration_rms"], 1e-3 / root2, rel=0.03)
        self.assertClose(windows[1]["vibration_rms"], 0.6e-3 / root2, rel=0.03)
        self.assertClose(out["vibration_rms_events"], 1e-3 / root2, rel=0.03)
        self.assertEqual([w["events"] for w in windows], ["hold", "release"])
        self.assertEqual(out["vibration_rms_after_hold"], windows[0]["vibration_rms"])
        self.assertEqual(out["vibration_rms_after_release"], windows[1]["vibration_rms"])
        self.assertTrue(math.isnan(out["vibration_rms_after_attach"]))
        self.assertClose(out["vibration_rms_final"], 0.3e-3 / root2, rel=0.03)
        self.assertClose(out["vibration_rms_holding"], 2e-3 / root2, rel=0.03)
        self.assertClose(out["hand_jitter_rms_holding"], jitter / root2, rel=0.03)
        self.assertClose(out["hand_jitter_rms_final"], jitter / root2, rel=0.03)
        self.assertEqual(out["contact_switch_rate_final"], 0.0)
        # The slowest event settles: the release, 0.05 ln(0.5 / 0.01) s.
        self.assertGreaterEqual(out["settle_time"], 0.05 * math.log(50) - 1e-12)
        self.assertLessEqual(out["settle_time"], 0.05 * math.log(50) + 1e-3)

        # run_metrics reports the same, and the windows for metrics.json.
        all_out, all_windows = metrics.run_metrics(self.directory, self.row(), {})
        self.assertEqual(all_out["vibration_rms_holding"], out["vibration_rms_holding"])
        self.assertEqual(len(all_windows), 2)

    def test_an_attach_window_does_not_end_at_its_attach_fixed(self):
        # attach_fixed comes attach_iterations steps after the attach (50 ms for an explicit run,
        # never within the run for an implicit one at 1/30 s): the window after the attach is
        # 0.5 s for every method, bounded by the input's next event, not by it.
        run = self.make_run()
        runfolder.write_summary(run, [{"t": 0.2, "type": "attach", "hand": "left"},
                                      {"t": 0.25, "type": "attach_fixed", "hand": "left"},
                                      {"t": 0.6, "type": "release", "hand": "left"}],
                                runfolder.CLOTH_SCENE, sim_time=1.2)
        t = np.arange(1201) / 1000.0
        event = np.zeros(len(t), int)
        event[np.searchsorted(t, [0.2, 0.25, 0.6])] = 1
        d = runfolder.unit_directions(2)
        phase = 2 * np.pi * 250.0 * t[:, None] + np.arange(2)
        # 1 mm of vibration until the attached particle is fixed, none after it.
        x = (np.where(t < 0.25, 1e-3, 0.0)[:, None] * np.sin(phase))[:, :, None] * d
        runfolder.write_trace(run, t, x, np.zeros_like(x), event=event)
        out, windows = metrics.vibration(run, runfiles.read_json(run / "summary.json"))
        self.assertEqual([(w["window_start"], w["window_end"], w["events"]) for w in windows],
                         [(0.2, 0.6, "attach"), (0.25, 0.6, "attach_fixed"), (0.6, 1.1, "release")])
        # 1 mm over the first 50 ms of the 400 ms window: RMS 1e-3 / sqrt(2) sqrt(50 / 400).
        self.assertClose(out["vibration_rms_after_attach"], 1e-3 / math.sqrt(2) * math.sqrt(0.05 / 0.4), rel=0.05)
        self.assertLess(out["vibration_rms_after_attach_fixed"], 1e-6)

    def test_run_without_events_settles_from_the_start(self):
        run = self.make_run()
        runfolder.write_summary(run, [{"t": 0.5, "type": "ignored"}], runfolder.CLOTH_SCENE, sim_time=1.0)
        t = np.arange(1001) / 1000.0
        d = runfolder.unit_directions(2)
        v = (0.2 * np.exp(-t / 0.1))[:, None, None] * d[None]
        runfolder.write_trace(run, t, np.zeros_like(v), v)
        out, windows = metrics.vibration(run, runfiles.read_json(run / "summary.json"))
        self.assertEqual(windows, [])
        self.assertGreaterEqual(out["settle_time"], 0.1 * math.log(20) - 1e-12)
        self.assertLessEqual(out["settle_time"], 0.1 * math.log(20) + 1e-3)
        self.assertTrue(math.isnan(out["vibration_rms_events"]))
        self.assertTrue(math.isnan(out["vibration_rms_holding"]), "no hold")
        self.assertTrue(math.isnan(out["hand_jitter_rms_final"]), "no hands.csv: no value")
        self.assertEqual(out["vibration_rms_final"], 0.0)

    def test_hands_never_tracked(self):
        hands = pd.DataFrame({"t": np.arange(100) / 1000.0, "hand": "left", "available": 0.0,
                              "x": 1.0, "y": 1.0, "z": 1.0})
        self.assertEqual(metrics.hand_jitter(hands, 0.0, 1.0, 3.0), 0.0)

    def test_no_trace(self):
        run = self.make_run()
        runfolder.write_summary(run)
        self.assertEqual(metrics.vibration(run, {}), ({}, []))


if __name__ == "__main__":
    unittest.main()
