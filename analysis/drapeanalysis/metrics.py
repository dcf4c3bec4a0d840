"""Metrics of one run, computed from its files only; formulas in docs/analysis.md."""
import csv
import math

import numpy as np

from . import runfiles

# Defaults of the vibration metrics (docs/analysis.md): window after an event, moving-average
# span that separates slow draping motion from vibration, and the speed below which cloth rests.
VIBRATION_WINDOW = 0.5
SMOOTHING_SPAN = 0.05
SETTLE_SPEED = 0.01


def energy_drift(energy):
    """Relative energy error r(t) = (E(t) - E(0)) / |E(0)|: its max and final magnitude, linear
    growth rate [1/s], and the exponent p of the envelope max_{s<=t}|r(s)| ~ t^p."""
    t, total = energy["t"], energy["total"]
    rel = np.abs(total - total[0]) / max(abs(total[0]), 1e-300)
    out = {
        "energy_drift_max_rel": float(rel.max()),
        "energy_drift_final_rel": float(rel[-1]),
        "energy_drift_rate": math.nan,
        "energy_drift_exponent": math.nan,
    }
    if len(t) < 3 or t[-1] <= 0:
        return out
    out["energy_drift_rate"] = float(np.polyfit(t, rel, 1)[0])
    envelope = np.maximum.accumulate(rel)
    late = (t >= 0.1 * t[-1]) & (envelope > 0)
    if late.sum() >= 3:
        out["energy_drift_exponent"] = float(np.polyfit(np.log(t[late]), np.log(envelope[late]), 1)[0])
    return out


def moving_average(values, span):
    """Centred moving average over `span` samples along axis 0; near the ends the span shrinks
    symmetrically, so the average stays centred and linear motion drops out everywhere."""
    half = max(span // 2, 0)
    cumulative = np.cumsum(np.concatenate([np.zeros((1,) + values.shape[1:]), values]), axis=0)
    k = np.arange(len(values))
    reach = np.minimum(half, np.minimum(k, len(values) - 1 - k))
    lo, hi = k - reach, k + reach + 1
    shape = (-1,) + (1,) * (values.ndim - 1)
    return (cumulative[hi] - cumulative[lo]) / (hi - lo).reshape(shape)


def high_frequency_rms(values, times, span_seconds):
    """RMS of values minus their moving average over span_seconds (axis 0 is time)."""
    if len(times) < 3:
        return math.nan
    step = float(np.median(np.diff(times)))
    span = max(int(round(span_seconds / step)) if step > 0 else 1, 1)
    residual = values - moving_average(values, span)
    return float(np.sqrt(np.mean(np.sum(residual**2, axis=-1))))


def settle_time(times, speeds, start, limit=SETTLE_SPEED):
    """Time after `start` from which the RMS speed stays below `limit` (nan if it never does)."""
    above = np.nonzero(speeds >= limit)[0]
    if len(above) == 0:
        return 0.0
    if above[-1] == len(times) - 1:
        return math.nan
    return float(times[above[-1] + 1] - start)


def vibration_window(trace, t0, t1, hands=None):
    """Vibration of the free particles over trace frames in [t0, t1]: high-frequency position
    and velocity RMS, settle time, contact switches per particle-second, and the hand jitter."""
    frames = (trace["t"] >= t0 - 1e-12) & (trace["t"] <= t1 + 1e-12)
    times = trace["t"][frames]
    free = ~trace["fixed"][frames].any(axis=0)
    out = {"window_start": t0, "window_end": t1, "frames": int(frames.sum())}
    if frames.sum() < 3 or not free.any():
        return out
    x = trace["x"][frames][:, free]
    v = trace["v"][frames][:, free]
    contact = trace["contact"][frames][:, free]
    speeds = np.sqrt(np.mean(np.sum(v**2, axis=-1), axis=1))
    switches = np.count_nonzero(np.diff(contact, axis=0))
    out.update({
        "vibration_rms": high_frequency_rms(x, times, SMOOTHING_SPAN),
        "vibration_velocity_rms": high_frequency_rms(v, times, SMOOTHING_SPAN),
        "settle_time": settle_time(times, speeds, t0),
        "contact_switch_rate": switches / (free.sum() * max(times[-1] - times[0], 1e-300)),
        "hand_jitter_rms": hand_jitter(hands, t0, t1) if hands is not None else math.nan,
    })
    return out


def hand_jitter(hands, t0, t1):
    """High-frequency RMS of the tracked hand positions in [t0, t1] (0 with no tracked hand)."""
    values = []
    for hand in np.unique(hands["hand_id"]):
        rows = (hands["hand_id"] == hand) & (hands["available"] > 0)
        rows &= (hands["t"] >= t0) & (hands["t"] <= t1)
        if rows.sum() >= 3:
            xyz = np.stack([hands["x"][rows], hands["y"][rows], hands["z"][rows]], axis=1)
            values.append(high_frequency_rms(xyz, hands["t"][rows], SMOOTHING_SPAN))
    return max(values) if values else 0.0


def read_hands(path):
    """hands.csv with the hand name turned into a number (left 0, right 1)."""
    header = runfiles.read_header(path)
    missing = [c for c in ("t", "hand", "available", "x", "y", "z") if c not in header]
    if missing:
        raise ValueError(f"{path}: missing column(s) {', '.join(missing)} (has {', '.join(header)})")
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    columns = {key: np.array([float(r[key]) for r in rows]) for key in ("t", "available", "x", "y", "z")}
    columns["hand_id"] = np.array([0 if r["hand"] == "left" else 1 for r in rows])
    return columns


def vibration(run, summary, window=VIBRATION_WINDOW):
    """Vibration after every event (to the next event or `window` seconds) and over the last
    `window` seconds of the run, from trace.csv; empty without a trace."""
    if not (run / "trace.csv").exists():
        return {}, []
    trace = runfiles.read_trace(run / "trace.csv")
    hands = read_hands(run / "hands.csv") if (run / "hands.csv").exists() else None
    end = float(trace["t"][-1])
    times = sorted({float(e["t"]) for e in summary.get("events", []) if e.get("type") != "ignored"})
    windows = []
    for k, t0 in enumerate(times):
        t1 = min(t0 + window, times[k + 1] if k + 1 < len(times) else end, end)
        windows.append(vibration_window(trace, t0, t1, hands))
    final = vibration_window(trace, max(end - window, 0.0), end, hands)
    out = {f"{key}_final": final.get(key, math.nan)
           for key in ("vibration_rms", "vibration_velocity_rms", "contact_switch_rate", "hand_jitter_rms")}
    events = [w for w in windows if "vibration_rms" in w]
    out["vibration_rms_events"] = max((w["vibration_rms"] for w in events), default=math.nan)
    # Steady holding: from `window` seconds after a hold (its transient gone) to the next event;
    # vibration that follows the hand here, with hand_jitter_rms, is the sensor's.
    holding = []
    holds = sorted(float(e["t"]) for e in summary.get("events", []) if e.get("type") == "hold")
    for t0 in holds:
        later = [t for t in times if t > t0 + 1e-12]
        t1 = min(later[0] if later else end, end)
        if t1 - (t0 + window) >= window:
            holding.append(vibration_window(trace, t0 + window, t1, hands))
    holding = [w for w in holding if "vibration_rms" in w]
    worst = max(holding, key=lambda w: w["vibration_rms"], default={})
    out["vibration_rms_holding"] = worst.get("vibration_rms", math.nan)
    out["vibration_velocity_rms_holding"] = worst.get("vibration_velocity_rms", math.nan)
    out["hand_jitter_rms_holding"] = worst.get("hand_jitter_rms", math.nan)
    # Without events the cloth settles from its start; with events, from the slowest event.
    settling = events if times else [vibration_window(trace, 0.0, end, hands)]
    settle = [w.get("settle_time", math.nan) for w in settling]
    out["settle_time"] = max(settle) if settle and not any(map(math.isnan, settle)) else math.nan
    return out, windows


def nearest_distances(points, objects):
    """Distance from each point to its nearest object particle (brute force, in blocks)."""
    out = np.empty(len(points))
    for start in range(0, len(points), 256):
        block = points[start:start + 256]
        d2 = np.sum((block[:, None, :] - objects[None, :, :]) ** 2, axis=-1)
        out[start:start + 256] = np.sqrt(d2.min(axis=1))
    return out


def spring_strain(x, rows, cols, spacing):
    """Strain (L - L0) / L0 of the structural and shear springs of a rows x cols grid."""
    grid = x.reshape(rows, cols, 3)
    pairs = [
        (grid[:, :-1], grid[:, 1:], spacing),
        (grid[:-1, :], grid[1:, :], spacing),
        (grid[:-1, :-1], grid[1:, 1:], spacing * math.sqrt(2)),
        (grid[:-1, 1:], grid[1:, :-1], spacing * math.sqrt(2)),
    ]
    strains = [((np.linalg.norm(b - a, axis=-1) - rest) / rest).ravel() for a, b, rest in pairs]
    return np.concatenate(strains)


def mapping_error(run, summary):
    """Distance to the object minus the threshold, and spring strain, right after the first map
    (trace frame at the map event) and at the end (state.csv)."""
    maps = [e for e in summary.get("events", []) if e.get("type") == "map"]
    if not maps or not (run / "dummy.csv").exists() or not (run / "state.csv").exists():
        return {}
    dummy = runfiles.read_table(run / "dummy.csv", ("x", "y", "z"))
    objects = np.stack([dummy["x"], dummy["y"], dummy["z"]], axis=1)
    delta = runfiles.scene_value(summary, "collision.threshold", 0.01)
    rows = runfiles.scene_value(summary, "cloth.rows", 0)
    cols = runfiles.scene_value(summary, "cloth.cols", 0)
    spacing = runfiles.scene_value(summary, "cloth.spacing", 0.0)
    states = {}
    state = runfiles.read_table(run / "state.csv", ("x", "y", "z"))
    states["final"] = np.stack([state["x"], state["y"], state["z"]], axis=1)
    if (run / "trace.csv").exists():
        trace = runfiles.read_trace(run / "trace.csv")
        at_map = np.nonzero(trace["event"] & np.isclose(trace["t"], maps[0]["t"]))[0]
        if len(at_map):
            states["mapped"] = trace["x"][at_map[-1]]
    if rows * cols != len(states["final"]):
        raise ValueError(f"{run / 'summary.json'}: cloth.rows x cloth.cols = {rows} x {cols}, but "
                         f"{run / 'state.csv'} has {len(states['final'])} particles")
    out = {}
    for stage, x in states.items():
        gap = nearest_distances(x, objects) - delta
        strain = spring_strain(x, rows, cols, spacing)
        out[f"mapping_gap_mean_{stage}"] = float(np.mean(np.abs(gap)))
        out[f"mapping_gap_max_{stage}"] = float(np.max(np.abs(gap)))
        out[f"spring_strain_rms_{stage}"] = float(np.sqrt(np.mean(strain**2)))
        out[f"spring_strain_max_{stage}"] = float(np.max(np.abs(strain)))
    return out


def reference_error(run, reference_run):
    """RMS and max distance between the final particle positions of a run and its reference."""
    if not (run / "state.csv").exists() or not (reference_run / "state.csv").exists():
        return {}
    a = runfiles.read_table(run / "state.csv", ("x", "y", "z"))
    b = runfiles.read_table(reference_run / "state.csv", ("x", "y", "z"))
    if len(a["x"]) != len(b["x"]):
        raise ValueError(f"{run / 'state.csv'}: {len(a['x'])} particles, the reference "
                         f"{reference_run / 'state.csv'} has {len(b['x'])}")
    d = np.sqrt((a["x"] - b["x"]) ** 2 + (a["y"] - b["y"]) ** 2 + (a["z"] - b["z"]) ** 2)
    return {"error_rms": float(np.sqrt(np.mean(d**2))), "error_max": float(d.max())}


def run_metrics(directory, row, rows_by_id):
    """Every metric the files of one run support, and the per-event vibration windows."""
    run = runfiles.run_dir(directory, row)
    out, windows = {}, []
    if not (run / "summary.json").exists():
        return out, windows
    summary = runfiles.read_json(run / "summary.json")
    if (run / "energy.csv").exists():
        out.update(energy_drift(runfiles.read_table(run / "energy.csv", ("t", "total"))))
    vib, windows = vibration(run, summary)
    out.update(vib)
    out.update(mapping_error(run, summary))
    reference = rows_by_id.get(row.get("reference") or "")
    if reference is not None:
        out.update(reference_error(run, runfiles.run_dir(directory, reference)))
    return out, windows
