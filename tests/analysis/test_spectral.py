"""The spectral vibration metric and the cutoff from the model (drapeanalysis/spectral.py)
against closed forms."""
import math
import unittest

import numpy as np

import runfolder
import drapeanalysis
from drapeanalysis import spectral

CUTOFF = 3.449  # combination 1's cutoff (runfolder.CLOTH_SCENE), Hz
GRAVITY = np.array([0.0, -9.81, 0.0])


def times(rate, start=1.0, span=2.0):
    """Uniform sample times over [start, start + span] at `rate` Hz (both ends included)."""
    return start + np.arange(int(round(span * rate)) + 1) / rate


def free_fall(t, particles=3):
    """x_i(t) = x_i0 + v_i0 t + g t^2 / 2, (T, N, 3)."""
    x0 = np.array([[0.1, 1.3, 0.2], [0.3, 1.1, -0.1], [-0.2, 0.9, 0.4]])[:particles]
    v0 = np.array([[0.2, 0.5, -0.1], [0.0, -0.3, 0.2], [0.1, 0.0, 0.0]])[:particles]
    t = t[:, None, None]
    return x0 + v0 * t + 0.5 * GRAVITY * t**2


def swing(t, amplitude=0.05, frequency=0.81, particles=3):
    """A slow pendulum-like swing along x, a different phase per particle, (T, N, 3)."""
    phase = 2 * np.pi * frequency * t[:, None] + 0.4 * np.arange(particles)
    return amplitude * np.sin(phase)[:, :, None] * np.array([1.0, 0.0, 0.0])


def along(t, amplitude, frequency, direction, particles=3):
    """A sinusoid of the given amplitude along a unit direction, (T, N, 3)."""
    direction = np.asarray(direction, float) / np.linalg.norm(direction)
    phase = 2 * np.pi * frequency * t[:, None] + 0.7 * np.arange(particles)
    return amplitude * np.sin(phase)[:, :, None] * direction


class VibrationRmsTest(unittest.TestCase):
    def assertRel(self, actual, expected, rel):
        self.assertLessEqual(abs(actual - expected), rel * abs(expected), f"{actual!r} != {expected!r} (rel {rel})")

    def test_free_fall_reads_zero(self):
        # A free fall is quadratic in t, inside the detrending polynomial: what remains is
        # round-off of the least-squares fit on positions of order 1 m and 10 m/s^2 * 4 s^2
        # (double precision 1e-16 relative, times the fit's conditioning): below 1e-12 m.
        for rate in (200, 1000, 5000):
            t = times(rate)
            self.assertLess(drapeanalysis.vibration_rms(t, free_fall(t), CUTOFF), 1e-12, rate)

    def test_slow_swing_reads_zero(self):
        # A 5 cm swing at the pendulum frequency (0.81 Hz, a quarter of the cutoff) over 2 s: the
        # trend (degree 11 here) holds it but for its Legendre truncation, measured 2.4e-6 m;
        # below 1e-4 of the swing's amplitude. The old moving average read 0.98 mm on a fall.
        for rate in (200, 1000, 5000):
            t = times(rate)
            self.assertLess(drapeanalysis.vibration_rms(t, swing(t) + free_fall(t), CUTOFF), 5e-6, rate)

    def test_sinusoid_along_a_direction(self):
        # x_i = A sin(w t + phi_i) d with |d| = 1: |r|^2 = A^2 sin^2, its mean over whole periods
        # A^2 / 2: RMS A / sqrt 2. 40 Hz over 2 s: 80 periods. Tolerance 0.5 %: the end effects
        # (the mirrored signal's kink and the trend's share of the sinusoid) measured below 0.3 %.
        amplitude = 1e-3
        t = times(1000)
        got = drapeanalysis.vibration_rms(t, along(t, amplitude, 40.0, [1, 2, -1]), CUTOFF)
        self.assertRel(got, amplitude / math.sqrt(2), 0.005)

    def test_sinusoid_on_every_axis(self):
        # Amplitude A on each of x, y, z with independent phases: |r|^2 = A^2 (sin^2 a + sin^2 b
        # + sin^2 c), mean 3 A^2 / 2: RMS A sqrt(3 / 2), the 3-D norm's factor sqrt 3 on A / sqrt 2.
        amplitude = 1e-3
        t = times(1000)
        phases = 2 * np.pi * 40.0 * t[:, None, None] + np.array([0.0, 1.1, 2.3]) + 0.5 * np.arange(3)[None, :, None]
        got = drapeanalysis.vibration_rms(t, amplitude * np.sin(phases), CUTOFF)
        self.assertRel(got, amplitude * math.sqrt(1.5), 0.005)

    def test_same_value_at_every_sampling_rate(self):
        # Fall + swing + a 40 Hz sinusoid (below the 100 Hz Nyquist of the slowest rate): the
        # same reading at 200 Hz, 1 kHz and 5 kHz, within 0.2 % of each other.
        amplitude = 1e-3
        values = []
        for rate in (200, 1000, 5000):
            t = times(rate)
            x = free_fall(t) + swing(t) + along(t, amplitude, 40.0, [0, 1, 1])
            values.append(drapeanalysis.vibration_rms(t, x, CUTOFF))
        for value in values:
            self.assertRel(value, amplitude / math.sqrt(2), 0.005)
        self.assertLess(max(values) - min(values), 0.002 * min(values))

    def test_slow_plus_fast_gives_the_fast_part(self):
        # A 14.7 Hz sinusoid (the stretch mode) on a swing, over a short 0.5 s window, 7.35
        # periods: the reference is the sinusoid's own RMS over these samples; 2 % for the
        # window's ends, which weigh more in a short window.
        t = times(1000, span=0.5)
        fast = along(t, 2e-3, 14.7, [1, 0, 1])
        got = drapeanalysis.vibration_rms(t, swing(t) + fast, CUTOFF)
        self.assertRel(got, spectral.norm_rms(fast), 0.02)

    def test_slow_motion_beside_it(self):
        # slow^2 + fast^2 = mean |x - mean x|^2 but for the small overlap of the fast part with
        # the trend (1e-5 here); a swing of amplitude B over whole periods reads B / sqrt 2.
        t = times(1000, span=1 / 0.81 * 2)
        x = swing(t, 0.05) + along(t, 1e-3, 40.0, [1, 1, 0])
        slow = drapeanalysis.slow_motion_rms(t, x, CUTOFF)
        fast = drapeanalysis.vibration_rms(t, x, CUTOFF)
        total = spectral.norm_rms(x - x.mean(axis=0))
        self.assertRel(slow**2 + fast**2, total**2, 1e-4)
        self.assertRel(slow, 0.05 / math.sqrt(2), 0.005)

    def test_non_uniform_samples(self):
        # Times jittered by up to 40 % of the step are interpolated linearly onto a uniform grid:
        # a component at f loses at most 1 - cos(pi f h) (0.8 % at 40 Hz, h = 1 ms). Duplicate
        # times (an event frame) keep their last sample.
        amplitude = 1e-3
        t = times(1000) + np.random.default_rng(3).uniform(-0.4e-3, 0.4e-3, 2001) * np.r_[0, np.ones(1999), 0]
        x = free_fall(t) + along(t, amplitude, 40.0, [1, 0, 0])
        t, x = np.insert(t, 500, t[500]), np.insert(x, 500, x[500] + 5.0, axis=0)
        self.assertRel(drapeanalysis.vibration_rms(t, x, CUTOFF), amplitude / math.sqrt(2), 0.01)

    def test_cannot_split(self):
        t = times(200)
        x = along(t, 1e-3, 40.0, [1, 0, 0])
        self.assertTrue(math.isnan(drapeanalysis.vibration_rms(t, x, 100.0)), "cutoff at Nyquist")
        self.assertTrue(math.isnan(drapeanalysis.vibration_rms(t[:3], x[:3], CUTOFF)), "too few samples")
        with self.assertRaises(ValueError):
            drapeanalysis.vibration_rms(t[::-1], x, CUTOFF)


class ModelFrequenciesTest(unittest.TestCase):
    def test_combination_one_by_hand(self):
        # 20 x 20, spacing 0.02 m: sides L = 19 x 0.02 = 0.38 m. Swing sqrt(9.81 / 0.38) / 2 pi
        # = 0.80865 Hz. k = k_shear = 50 N/m: C11 = 100, C12 = 50, k_eff = 100 - 2500 / 100 = 75
        # N/m; c = 0.02 sqrt(75 / 6e-5) = 22.3607 m/s; pinned, fixed-free: c / (4 L) = 14.7110 Hz;
        # cutoff sqrt(0.80865 x 14.7110) = 3.44907 Hz.
        model = drapeanalysis.model_frequencies({"scene": runfolder.CLOTH_SCENE, "events": []})
        self.assertAlmostEqual(model["swing_hz"], 0.80865, places=5)
        self.assertAlmostEqual(model["k_effective"], 75.0, places=12)
        self.assertAlmostEqual(model["wave_speed"], 22.3607, places=4)
        self.assertAlmostEqual(model["stretch_hz"], 14.7110, places=4)
        self.assertAlmostEqual(model["cutoff_hz"], 3.44907, places=5)
        self.assertAlmostEqual(drapeanalysis.vibration_cutoff(runfolder.CLOTH_SCENE), 3.44907, places=5)

    def test_free_rectangle_without_shear(self):
        # 11 x 31, spacing 0.01: sides 0.1 and 0.3 m. Swing of the short side sqrt(9.81 / 0.1)
        # / 2 pi = 1.57636 Hz; no shear: k_eff = k = 20, c = 0.01 sqrt(20 / 1e-4) = 4.47214 m/s;
        # no pin, no hold: free-free c / (2 x 0.3) = 7.45356 Hz; cutoff sqrt of the product
        # 3.42775 Hz. A hold makes it fixed-free: c / (4 x 0.3) = 3.72678 Hz.
        scene = {"cloth": {"rows": 11, "cols": 31, "spacing": 0.01, "particle_mass": 1e-4,
                           "k_structural": 20, "k_shear": 0}}
        model = drapeanalysis.model_frequencies({"scene": scene, "events": []})
        self.assertAlmostEqual(model["swing_hz"], 1.57636, places=5)
        self.assertAlmostEqual(model["swing_slowest_hz"], math.sqrt(9.81 / 0.3) / (2 * math.pi), places=12)
        self.assertAlmostEqual(model["stretch_hz"], 7.45356, places=5)
        self.assertAlmostEqual(model["cutoff_hz"], 3.42775, places=5)
        held = drapeanalysis.model_frequencies({"scene": scene, "events": [{"t": 0.1, "type": "hold"}]})
        self.assertAlmostEqual(held["stretch_hz"], 3.72678, places=5)

    def test_bending_and_gravity(self):
        # k_bending adds 4 k_b to C11 (a spring over two spacings): 10 + 10 + 4 x 5 = 40,
        # k_eff = 40 - 100 / 40 = 37.5. Gravity [0, -4.9, 0]: swing sqrt(4.9 / 0.38) / 2 pi.
        scene = {"cloth": {"rows": 20, "cols": 20, "spacing": 0.02, "particle_mass": 6e-5,
                           "k_structural": 10, "k_bending": 5}, "gravity": [0, -4.9, 0], "pins": [[0, 0]]}
        model = drapeanalysis.model_frequencies(scene)
        self.assertAlmostEqual(model["k_effective"], 37.5, places=12)
        self.assertAlmostEqual(model["swing_hz"], math.sqrt(4.9 / 0.38) / (2 * math.pi), places=12)

    def test_scene_without_a_cloth(self):
        with self.assertRaises(ValueError):
            drapeanalysis.model_frequencies({"scene": {}})


if __name__ == "__main__":
    unittest.main()
