"""Spectral split of motion into slow (draping, swing) and fast (vibration) parts, and the cutoff
frequency between them derived from the cloth model; formulas in docs/analysis.md (Vibration).

Steps, per particle and coordinate, over the samples given:
1. uniform grid: duplicate times keep their last sample (a trace's event frame is written after
   the event changed the state); non-uniform times are linearly interpolated onto as many
   uniformly spaced times over the same span (uniform input is used as it is, exactly);
2. detrend: the least-squares Legendre series in t of degree p = max(2, ceil(pi T f_c / 2)) over
   the window of length T is removed. Degree p oscillates at up to about f_c / 2, so it holds
   only slow motion: constant acceleration (a free fall) exactly, a swing well below f_c almost
   entirely; fast motion is nearly orthogonal to it;
3. zero-phase high-pass: the rest is mirrored at its end (an even extension, so the periodic
   signal the FFT sees has no jump at the window's ends) and every FFT bin at or below the cutoff
   is set to zero; the first half of the inverse transform is the fast part.
The slow part is what remains of the motion about its mean position: x - mean - fast.
"""
import math

import numpy as np

MIN_DEGREE = 2
# The trend's highest frequency as a fraction of the cutoff: p = ceil(pi T f_c TREND_FRACTION).
TREND_FRACTION = 0.5
STANDARD_GRAVITY = 9.81


def uniform_samples(t, x):
    """(t, x) on uniformly spaced times over [t[0], t[-1]], as many samples as distinct times;
    duplicate times keep their last sample. t must not decrease."""
    t = np.asarray(t, dtype=float)
    x = np.asarray(x, dtype=float)
    if t.ndim != 1 or len(t) != len(x):
        raise ValueError(f"times {t.shape} and positions {x.shape} do not match")
    if np.any(np.diff(t) < 0):
        raise ValueError("times must not decrease")
    last = np.append(np.diff(t) > 0, True)  # the last sample at each time
    t, x = t[last], x[last]
    if len(t) < 2:
        return t, x
    grid = np.linspace(t[0], t[-1], len(t))
    if np.max(np.abs(t - grid)) <= 1e-9 * (t[-1] - t[0]):
        return grid, x
    # Linear interpolation of every column at once; the weight of the right neighbour is w.
    right = np.clip(np.searchsorted(t, grid, side="right"), 1, len(t) - 1)
    w = ((grid - t[right - 1]) / (t[right] - t[right - 1])).reshape((-1,) + (1,) * (x.ndim - 1))
    return grid, (1 - w) * x[right - 1] + w * x[right]


def trend_degree(span, cutoff_hz, samples):
    """Degree of the slow trend over a window of `span` seconds: max(2, ceil(pi T f_c / 2)),
    at most a third of the samples."""
    degree = max(MIN_DEGREE, math.ceil(math.pi * span * cutoff_hz * TREND_FRACTION))
    return min(degree, max(MIN_DEGREE, samples // 3))


def split_motion(t, x, cutoff_hz):
    """(grid times, slow, fast): x (T, ...) split at cutoff_hz on the uniform grid, slow about the
    mean position; None when there are fewer than MIN_DEGREE + 2 distinct times or the cutoff
    is not below the grid's Nyquist frequency."""
    grid, x = uniform_samples(t, x)
    n = len(grid)
    if n < MIN_DEGREE + 2 or not grid[-1] > grid[0]:
        return None
    span = grid[-1] - grid[0]
    step = span / (n - 1)
    if not 0 < cutoff_hz < 0.5 / step:
        return None
    flat = x.reshape(n, -1)
    # Legendre polynomials of the time scaled to [-1, 1]: a well-conditioned least-squares fit.
    u = (grid - grid[0]) / span * 2 - 1
    basis = np.polynomial.legendre.legvander(u, trend_degree(span, cutoff_hz, n))
    coefficients, *_ = np.linalg.lstsq(basis, flat, rcond=None)
    rest = flat - basis @ coefficients
    mirrored = np.concatenate([rest, rest[::-1]])
    spectrum = np.fft.rfft(mirrored, axis=0)
    spectrum[np.fft.rfftfreq(2 * n, step) <= cutoff_hz] = 0
    fast = np.fft.irfft(spectrum, 2 * n, axis=0)[:n]
    slow = flat - flat.mean(axis=0) - fast
    return grid, slow.reshape(x.shape), fast.reshape(x.shape)


def norm_rms(values):
    """sqrt(mean over time and particles of |v|^2), v the last axis (coordinates)."""
    return float(np.sqrt(np.mean(np.sum(values**2, axis=-1))))


def vibration_rms(t, x, cutoff_hz):
    """RMS over time and particles of the Euclidean norm of the motion above cutoff_hz [units of
    x]: t (T,) times, x (T, N, 3) or (T, 3). nan when split_motion cannot split."""
    split = split_motion(t, x, cutoff_hz)
    return math.nan if split is None else norm_rms(split[2])


def slow_motion_rms(t, x, cutoff_hz):
    """RMS of the motion about the mean position below cutoff_hz (the polynomial trend and the
    detrended rest below the cutoff); slow^2 + vibration^2 = mean |x - mean|^2 but for the fast
    part's small overlap with the trend. nan as above."""
    return split_rms(t, x, cutoff_hz)[0]


def split_rms(t, x, cutoff_hz):
    """(slow_motion_rms, vibration_rms) from one split (one FFT of the window)."""
    split = split_motion(t, x, cutoff_hz)
    return (math.nan, math.nan) if split is None else (norm_rms(split[1]), norm_rms(split[2]))


def _scene(summary):
    """The scene of a summary.json (or a scene itself)."""
    return summary.get("scene", summary)


def model_frequencies(summary):
    """Swing and stretch frequencies of the cloth of a run's summary.json (or scene) and the
    cutoff between them (docs/analysis.md, Cutoff from the model):
    swing_hz = sqrt(g / L) / 2 pi for each side L of the grid, the fastest (shortest side) counted;
    stretch_hz = c / (4 L_max) with a pin or a manipulation holding a particle (fixed-free),
    c / (2 L_max) for a free cloth, c = spacing sqrt(k_eff / m) with the plane-stress stiffness
    k_eff = C11 - C12^2 / C11, C11 = k_structural + k_shear + 4 k_bending, C12 = k_shear;
    cutoff_hz = sqrt(max swing_hz * stretch_hz)."""
    scene = _scene(summary)
    cloth = scene.get("cloth", {})
    rows, cols = int(cloth.get("rows", 0)), int(cloth.get("cols", 0))
    spacing, mass = float(cloth.get("spacing", 0.0)), float(cloth.get("particle_mass", 0.0))
    k = float(cloth.get("k_structural", 0.0))
    k_shear = float(cloth.get("k_shear", k))
    k_bending = float(cloth.get("k_bending", 0.0))
    g = float(np.linalg.norm(scene.get("gravity", [0.0, -STANDARD_GRAVITY, 0.0])))
    sides = [n * spacing for n in (rows - 1, cols - 1) if n > 0]
    if not sides or mass <= 0 or k <= 0 or g <= 0:
        raise ValueError("scene: cloth.rows/cols/spacing/particle_mass/k_structural and gravity "
                         f"give no swing and stretch frequency (rows {rows}, cols {cols}, "
                         f"spacing {spacing}, mass {mass}, k {k}, g {g})")
    c11 = k + k_shear + 4 * k_bending
    k_eff = c11 - k_shear**2 / c11
    wave_speed = spacing * math.sqrt(k_eff / mass)
    held = bool(scene.get("pins")) or any(e.get("type") in ("hold", "attach", "attach_fixed", "map")
                                          for e in summary.get("events", []))
    longest = max(sides)
    stretch = wave_speed / ((4 if held else 2) * longest)
    swings = sorted(math.sqrt(g / side) / (2 * math.pi) for side in sides)
    return {"swing_hz": swings[-1], "swing_slowest_hz": swings[0], "stretch_hz": stretch,
            "cutoff_hz": math.sqrt(swings[-1] * stretch), "wave_speed": wave_speed,
            "k_effective": k_eff, "fixed_free": held, "separated": stretch > swings[-1]}


def vibration_cutoff(summary):
    """The cutoff [Hz] between a run's swing and stretch frequencies (model_frequencies)."""
    return model_frequencies(summary)["cutoff_hz"]
