"""Metrics of one run, computed from its files only; formulas in docs/analysis.md."""
import math

import numpy as np

from . import runfiles, spectral
from .run_series import read_run_event_trace, read_run_restart_error, read_run_series

# Defaults of the vibration metrics (docs/analysis.md): window after an event and the speed
# below which cloth rests. The cutoff between slow motion and vibration comes from the model
# (spectral.model_frequencies).
VIBRATION_WINDOW = 0.5
# The events whose windows get a vibration column each (vibration_rms_after_<kind>).
EVENT_KINDS = ("hold", "release", "attach", "attach_fixed", "map")
SETTLE_SPEED = 0.01
# Horizon of the short-horizon error against the reference: one Kinect frame, what the user sees
# next (docs/analysis.md, "Error against the reference").
SHORT_HORIZON = 1.0 / 30.0
# Frames of a run and of its reference are the same instant when their times agree this well
# (both are t_e + k dt_trace computed the same way).
SAME_INSTANT = 1e-9
# The drift columns drapelab's summary.json gives (experiments/runner/run_scene.cpp), emptied with
# the analysis's own for a run that did not finish.
SUMMARY_DRIFT = ("energy_drift_max_abs", "energy_drift_max_rel", "energy_drift_final_rel",
                 "energy_rise_max_rel")


def energy_drift(energy):
    """Relative energy error r(t) = (E(t) - E(0)) / |E(0)|: its max and final magnitude, linear
    growth rate [1/s], and the exponent p of the envelope max_{s<=t}|r(s)| ~ t^p."""
    t, total = np.asarray(energy["t"], float), np.asarray(energy["total"], float)
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


def settle_time(times, speeds, start, limit=SETTLE_SPEED):
    """Time after `start` from which the RMS speed stays below `limit` (nan if it never does)."""
    above = np.nonzero(speeds >= limit)[0]
    if len(above) == 0:
        return 0.0
    if above[-1] == len(times) - 1:
        return math.nan
    return float(times[above[-1] + 1] - start)


def vibration_window(trace, t0, t1, cutoff_hz, hands=None):
    """Vibration of the free particles over trace frames in [t0, t1]: position and velocity RMS
    above cutoff_hz and the slow motion beside it (spectral.py), settle time, contact switches
    per particle-second, and the hand jitter."""
    frames = (trace["t"] >= t0 - 1e-12) & (trace["t"] <= t1 + 1e-12)
    times = trace["t"][frames]
    out = {"window_start": t0, "window_end": t1, "frames": int(frames.sum())}
    if frames.sum() < 3:
        return out
    out["sample_hz"] = (len(times) - 1) / max(times[-1] - times[0], 1e-300)
    free = ~trace["fixed"][frames].any(axis=0)
    if not free.any():
        return out
    x = trace["x"][frames][:, free]
    v = trace["v"][frames][:, free]
    contact = trace["contact"][frames][:, free]
    speeds = np.sqrt(np.mean(np.sum(v**2, axis=-1), axis=1))
    switches = np.count_nonzero(np.diff(contact, axis=0))
    slow, fast = spectral.split_rms(times, x, cutoff_hz)
    out.update({
        "vibration_rms": fast,
        "slow_motion_rms": slow,
        "vibration_velocity_rms": spectral.vibration_rms(times, v, cutoff_hz),
        "settle_time": settle_time(times, speeds, t0),
        "contact_switch_rate": switches / (free.sum() * max(times[-1] - times[0], 1e-300)),
        "hand_jitter_rms": hand_jitter(hands, t0, t1, cutoff_hz) if hands is not None else math.nan,
    })
    return out


def hand_jitter(hands, t0, t1, cutoff_hz):
    """RMS above cutoff_hz of the tracked hand positions (hands.csv DataFrame) in [t0, t1], the
    largest over the hands (0 with no tracked hand)."""
    values = []
    inside = (hands["available"] > 0) & (hands["t"] >= t0) & (hands["t"] <= t1)
    for _, rows in hands[inside].groupby("hand"):
        if len(rows) >= 3:
            values.append(spectral.vibration_rms(rows["t"].to_numpy(), runfiles.positions(rows), cutoff_hz))
    values = [v for v in values if math.isfinite(v)]
    return max(values) if values else 0.0


def _event_times(summary):
    """The times of a run's events (ignored keys left out), each once, in order."""
    return sorted({float(e["t"]) for e in summary.get("events", []) if e.get("type") != "ignored"})


def attach_unfixed(summary):
    """How many of a run's attaches were never fixed: `attach` events without their
    `attach_fixed` (docs/outputs.md, summary.json `events`). An attached particle is fixed
    `attach_iterations` steps after its attach (docs/model.md section 7), so an attach late in
    the run, or in a run that stopped, has no attach error: a failed attach, where a run
    without any attach has none because none applies (docs/analysis.md, Attach error)."""
    kinds = [e.get("type") for e in summary.get("events", [])]
    if "attach" not in kinds:  # nothing to fix: the metric does not apply
        return {}
    return {"attach_unfixed_count": kinds.count("attach") - kinds.count("attach_fixed")}


def vibration(run, summary, window=VIBRATION_WINDOW):
    """Vibration after every event (to the next event or `window` seconds) and over the last
    `window` seconds of the run, above the cutoff derived from the run's scene. The windows after
    events come from event_trace/ when the run wrote one (a fixed fine rate), else from
    trace.csv; the last window and the steady holding from trace.csv. Empty without either."""
    coarse_file, fine = run / "trace.csv", read_run_event_trace(run, summary)
    if not coarse_file.exists() and fine is None:
        return {}, []
    try:
        model = spectral.model_frequencies(summary)
    except ValueError as e:
        raise ValueError(f"{run / 'summary.json'}: {e}") from e
    cutoff = model["cutoff_hz"]
    trace = (runfiles.trace_frames(read_run_series(run, summary, "trace.csv")) if coarse_file.exists()
             else None)
    hands = read_run_series(run, summary, "hands.csv") if (run / "hands.csv").exists() else None
    after_events = fine if fine is not None else trace
    end = float((trace if trace is not None else fine)["t"][-1])
    times = _event_times(summary)
    # A window ends at the next event of the input, not at an attach_fixed: that one comes
    # attach_iterations steps after its attach, so at a time that depends on the step, and would
    # cut an explicit run's window after an attach to 50 ms where an implicit run's (whose attach
    # does not complete) runs 0.5 s: the same metric over windows of different lengths.
    ends = sorted({float(e["t"]) for e in summary.get("events", [])
                   if e.get("type") not in ("ignored", "attach_fixed")})

    def next_end(t0):
        """The input's next event after t0, else the run's end."""
        return next((t for t in ends if t > t0 + 1e-12), end)

    windows = []
    for t0 in times:
        t1 = min(t0 + window, next_end(t0), end)
        windows.append(vibration_window(after_events, t0, t1, cutoff, hands))
        windows[-1]["events"] = "+".join(sorted({e["type"] for e in summary.get("events", [])
                                                 if e.get("type") != "ignored" and float(e["t"]) == t0}))
    if trace is None:  # no trace.csv: the last and the holding windows have no frames
        trace = {"t": np.empty(0)}
    final = vibration_window(trace, max(end - window, 0.0), end, cutoff, hands)
    out = {f"{key}_final": final.get(key, math.nan)
           for key in ("vibration_rms", "slow_motion_rms", "vibration_velocity_rms", "contact_switch_rate",
                       "hand_jitter_rms")}
    out.update(vibration_cutoff_hz=cutoff, swing_hz=model["swing_hz"], stretch_hz=model["stretch_hz"])
    events = [w for w in windows if math.isfinite(w.get("vibration_rms", math.nan))]
    worst_event = max(events, key=lambda w: w["vibration_rms"], default={})
    out["vibration_rms_events"] = worst_event.get("vibration_rms", math.nan)
    out["slow_motion_rms_events"] = worst_event.get("slow_motion_rms", math.nan)
    out["vibration_sample_hz_events"] = worst_event.get("sample_hz", math.nan)
    # Per kind of event (the largest window that starts with one): which manipulation excites
    # the vibration, and whether a remedy for it works (docs/findings.md).
    for kind in EVENT_KINDS:
        of_kind = [w["vibration_rms"] for w in events if kind in w["events"].split("+")]
        out[f"vibration_rms_after_{kind}"] = max(of_kind, default=math.nan)
    # Steady holding: from `window` seconds after a hold (its transient gone) to the next event;
    # vibration that follows the hand here, with hand_jitter_rms, is the sensor's.
    holding = []
    holds = sorted(float(e["t"]) for e in summary.get("events", []) if e.get("type") == "hold")
    for t0 in holds:
        t1 = min(next_end(t0), end)
        if t1 - (t0 + window) >= window:
            holding.append(vibration_window(trace, t0 + window, t1, cutoff, hands))
    holding = [w for w in holding if math.isfinite(w.get("vibration_rms", math.nan))]
    worst = max(holding, key=lambda w: w["vibration_rms"], default={})
    out["vibration_rms_holding"] = worst.get("vibration_rms", math.nan)
    out["slow_motion_rms_holding"] = worst.get("slow_motion_rms", math.nan)
    out["vibration_velocity_rms_holding"] = worst.get("vibration_velocity_rms", math.nan)
    out["hand_jitter_rms_holding"] = worst.get("hand_jitter_rms", math.nan)
    # Without events the cloth settles from its start; with events, from the slowest event.
    settling = events if times else [vibration_window(trace, 0.0, end, cutoff, hands)]
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


# Spring families of the grid: along a row (between columns; around the body after a map),
# along a column (between rows; down the body) and the two diagonals.
SPRING_FAMILIES = ("along_rows", "along_cols", "shear")


def spring_strain(x, rows, cols, spacing):
    """Strain (L - L0) / L0 of the structural and shear springs of a rows x cols grid, by family
    (SPRING_FAMILIES)."""
    grid = x.reshape(rows, cols, 3)

    def strain(a, b, rest):
        return ((np.linalg.norm(b - a, axis=-1) - rest) / rest).ravel()

    diagonal = spacing * math.sqrt(2)
    return {"along_rows": strain(grid[:, :-1], grid[:, 1:], spacing),
            "along_cols": strain(grid[:-1, :], grid[1:, :], spacing),
            "shear": np.concatenate([strain(grid[:-1, :-1], grid[1:, 1:], diagonal),
                                     strain(grid[:-1, 1:], grid[1:, :-1], diagonal)])}


def mapping_error(run, summary):
    """Distance to the object minus the threshold, and spring strain, right after the first map
    (trace frame at the map event) and at the end (state.csv)."""
    maps = [e for e in summary.get("events", []) if e.get("type") == "map"]
    if not maps or not (run / "dummy.csv").exists() or not (run / "state.csv").exists():
        return {}
    objects = runfiles.positions(runfiles.read_table(run / "dummy.csv", ("x", "y", "z")))
    delta = runfiles.scene_value(summary, "collision.threshold", 0.01)
    rows = runfiles.scene_value(summary, "cloth.rows", 0)
    cols = runfiles.scene_value(summary, "cloth.cols", 0)
    spacing = runfiles.scene_value(summary, "cloth.spacing", 0.0)
    states = {}
    states["final"] = runfiles.positions(runfiles.read_state(run / "state.csv"))
    if (run / "trace.csv").exists():
        trace = runfiles.trace_frames(read_run_series(run, summary, "trace.csv"))
        at_map = np.nonzero(trace["event"] & np.isclose(trace["t"], maps[0]["t"]))[0]
        if len(at_map):
            states["mapped"] = trace["x"][at_map[-1]]
    if rows * cols != len(states["final"]):
        raise ValueError(f"{run / 'summary.json'}: cloth.rows x cloth.cols = {rows} x {cols}, but "
                         f"{run / 'state.csv'} has {len(states['final'])} particles")
    out = {}
    for stage, x in states.items():
        gap = nearest_distances(x, objects) - delta
        families = spring_strain(x, rows, cols, spacing)
        strain = np.concatenate(list(families.values()))
        out[f"mapping_gap_mean_{stage}"] = float(np.mean(np.abs(gap)))
        out[f"mapping_gap_max_{stage}"] = float(np.max(np.abs(gap)))
        out[f"spring_strain_rms_{stage}"] = float(np.sqrt(np.mean(strain**2)))
        out[f"spring_strain_max_{stage}"] = float(np.max(np.abs(strain)))
        # Which springs carry it: around the body (the layout's arc lengths and the offset by
        # delta) or down it (rows placed by height); docs/analysis.md, Mapping error.
        for family, values in families.items():
            out[f"spring_strain_rms_{stage}_{family}"] = float(np.sqrt(np.mean(values**2))) if len(values) else math.nan
            out[f"spring_strain_mean_{stage}_{family}"] = float(np.mean(values)) if len(values) else math.nan
    return out


def reference_error(run, reference_run):
    """RMS and max distance between the final particle positions of a run and its reference."""
    if not (run / "state.csv").exists() or not (reference_run / "state.csv").exists():
        return {}
    a = runfiles.positions(runfiles.read_state(run / "state.csv"))
    b = runfiles.positions(runfiles.read_state(reference_run / "state.csv"))
    if len(a) != len(b):
        raise ValueError(f"{run / 'state.csv'}: {len(a)} particles, the reference "
                         f"{reference_run / 'state.csv'} has {len(b)}")
    d = np.linalg.norm(a - b, axis=1)
    return {"error_rms": float(np.sqrt(np.mean(d**2))), "error_max": float(d.max())}


def _distance_rms(run_trace, reference_trace, t):
    """RMS over particles of the distance between a run and its reference at the run's frame
    nearest to t (within half a frame interval), or None when the run has no frame there or the
    reference none at the same instant."""
    times = run_trace["t"]
    i = int(np.argmin(np.abs(times - t)))
    spacing = float(np.median(np.diff(times))) if len(times) > 1 else 0.0
    if abs(times[i] - t) > 0.5 * spacing + SAME_INSTANT:
        return None
    j = int(np.argmin(np.abs(reference_trace["t"] - times[i])))
    if abs(reference_trace["t"][j] - times[i]) > SAME_INSTANT:
        return None
    d = np.linalg.norm(run_trace["x"][i] - reference_trace["x"][j], axis=1)
    return float(np.sqrt(np.mean(d**2)))


def short_horizon_error(run, reference_run, horizon=SHORT_HORIZON):
    """Error against the reference over a short horizon, from both runs' event traces (the same
    seeded initial state, frames at the same instants): `horizon` after the start
    (`short_error_start`), and averaged over the events at the same time in both runs: at the
    event (`short_error_events_inherited`, what the run brings into it) and `horizon` after it
    (`short_error_events`). Empty without both event traces (docs/analysis.md)."""
    mine, theirs = read_run_event_trace(run), read_run_event_trace(reference_run)
    if mine is None or theirs is None:
        return {}
    if mine["x"].shape[1:] != theirs["x"].shape[1:]:
        raise ValueError(f"{run / 'event_trace'}: {mine['x'].shape[1]} particles, the reference "
                         f"{reference_run / 'event_trace'} has {theirs['x'].shape[1]}")
    # The first window starts at the run's start (docs/outputs.md, event_trace/).
    start = _distance_rms(mine, theirs, float(mine["t"][0]) + horizon)
    # The same instant within SAME_INSTANT, not bit for bit: a fine reference's many steps sum
    # to a keyed event's time with round-off (1.4999999999977 s for a key at 1.5 s).
    shared = np.array(_event_times(runfiles.read_summary(reference_run)))
    at, after = [], []
    for t in _event_times(runfiles.read_summary(run)):
        if not len(shared) or np.min(np.abs(shared - t)) > SAME_INSTANT:
            continue
        before, later = _distance_rms(mine, theirs, t), _distance_rms(mine, theirs, t + horizon)
        if before is not None and later is not None:
            at.append(before)
            after.append(later)
    return {"short_error_start": math.nan if start is None else start,
            "short_error_events_inherited": float(np.mean(at)) if at else math.nan,
            "short_error_events": float(np.mean(after)) if after else math.nan,
            "short_error_events_n": len(after)}


def restart_error(run, summary):
    """The restart error (docs/analysis.md, "Restart error") from restart_error.csv. At the first
    horizon: `restart_error_start` (from the common start), `restart_error_events` (mean over
    the branches after the reference's events), `restart_error_after_<kind>` (over the events of
    one kind), `restart_error_events_rel` (mean of error / the reference's own motion over the
    horizon), `restart_motion_events` (the mean of that motion); for every later horizon
    `restart_error_events_<ms>ms` and, for the kinds that happened, `restart_error_after_<kind>_<ms>ms`;
    `restart_error_failed`, the branches that diverged or failed (left out of the means). Empty
    without the file."""
    path = run / "restart_error.csv"
    if not path.exists():
        return {}
    rows = read_run_restart_error(run, summary)
    out = {"restart_error_failed": int((rows["status"] != "ok").sum())}
    horizons = sorted(rows["horizon"].unique())
    for k, horizon in enumerate(horizons):
        at = rows[(rows["horizon"] == horizon) & (rows["status"] == "ok")]
        events = at[at["events"] != "start"]
        mean = float(events["error_rms"].mean()) if len(events) else math.nan
        if k > 0:
            out[f"restart_error_events_{1e3 * horizon:.0f}ms"] = mean
            # Per kind too: the accuracy-cost figure's later panel is the error after the hold.
            for kind in EVENT_KINDS:
                of_kind = events[events["events"] == kind]["error_rms"]
                if len(of_kind):
                    out[f"restart_error_after_{kind}_{1e3 * horizon:.0f}ms"] = float(of_kind.mean())
            continue
        start = at[at["events"] == "start"]["error_rms"]
        out["restart_error_start"] = float(start.iloc[0]) if len(start) else math.nan
        out["restart_error_events"] = mean
        out["restart_error_events_rel"] = (float((events["error_rms"] / events["reference_motion_rms"]).mean())
                                           if len(events) else math.nan)
        out["restart_motion_events"] = float(events["reference_motion_rms"].mean()) if len(events) else math.nan
        for kind in EVENT_KINDS:
            of_kind = events[events["events"] == kind]["error_rms"]
            out[f"restart_error_after_{kind}"] = float(of_kind.mean()) if len(of_kind) else math.nan
    return out


def run_metrics(directory, row, rows_by_id):
    """Every metric the files of one run support, and the per-event vibration windows."""
    run = runfiles.run_dir(directory, row)
    out, windows = {}, []
    if not (run / "summary.json").exists():
        return out, windows
    summary = runfiles.read_summary(run)
    if (run / "energy.csv").exists():
        drift = energy_drift(read_run_series(run, summary, "energy.csv"))
        if summary.get("status") != "ok":
            # A run that stopped early has no drift to compare with a finished run's: one that
            # diverged before its first energy row would read 0 (docs/analysis.md, Energy drift).
            drift = dict.fromkeys(list(drift) + list(SUMMARY_DRIFT), math.nan)
        out.update(drift)
    out.update(attach_unfixed(summary))
    vib, windows = vibration(run, summary)
    out.update(vib)
    out.update(mapping_error(run, summary))
    out.update(restart_error(run, summary))
    reference = rows_by_id.get(row.get("reference") or "")
    if reference is not None:
        out.update(reference_error(run, runfiles.run_dir(directory, reference)))
        out.update(short_horizon_error(run, runfiles.run_dir(directory, reference)))
    return out, windows
