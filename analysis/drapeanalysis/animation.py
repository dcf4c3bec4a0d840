"""An MP4 of one run's trace: the shaded front and side views of snapshots.py over time
(matplotlib.animation with the ffmpeg writer; ffmpeg from install_dependencies.sh)."""
import errno
import os
import signal
import subprocess

import matplotlib.pyplot as plt
import numpy as np
from matplotlib import animation

from . import runfiles, snapshots, style
from .run_series import read_run_series
from .fileio import atomic_output

MAX_FRAMES = 300
FPS = 25


def available():
    """True when matplotlib finds the ffmpeg program it writes MP4 with."""
    return animation.FFMpegWriter.isAvailable()


def ffmpeg_failure(error):
    """Why ffmpeg stopped (a CalledProcessError): most often it could not write the file, so the
    report counts it as a failed write (fileio.atomic_output) and says it in ffmpeg's last words.
    Python starts it with SIGXFSZ at its default, so a file size limit kills it."""
    if error.returncode == -signal.SIGXFSZ:
        return f"{os.strerror(errno.EFBIG)} (ffmpeg stopped by SIGXFSZ)"
    words = (error.stderr or "").strip().splitlines()
    return f"ffmpeg failed ({words[-1] if words else f'exit {error.returncode}'})"


def animate_run(run, out_file, max_frames=MAX_FRAMES, fps=FPS):
    """Writes out_file (MP4): the run's trace frames, evenly thinned to at most max_frames, front
    and side views side by side, played at fps frames a second. Returns out_file."""
    summary = runfiles.read_summary(run)
    trace = runfiles.trace_frames(read_run_series(run, summary, "trace.csv"))
    rows, cols = snapshots.cloth_grid(run, summary, trace)
    objects, points = snapshots.object_surface(run)
    frames = np.unique(np.linspace(0, len(trace["t"]) - 1, min(max_frames, len(trace["t"]))).astype(int))
    all_x = trace["x"].reshape(-1, 3)
    lo, hi = all_x.min(axis=0) - 0.05, all_x.max(axis=0) + 0.05
    fig, axes = plt.subplots(1, 2, figsize=(8, 4.5))
    events = sorted((float(e["t"]), e["type"]) for e in summary.get("events", []) if e.get("type") != "ignored")

    def draw(k):
        for ax, view in zip(axes, snapshots.VIEWS):
            ax.clear()
            horizontal = snapshots.VIEWS[view][0]
            x = trace["x"][k]
            cloth = snapshots.cloth_quads(x, rows, cols)
            snapshots.draw_view(ax, view, cloth, snapshots.shade(cloth, snapshots.CLOTH_RGB, view),
                                objects, points, x[trace["fixed"][k]])
            ax.set_xlim(lo[horizontal], hi[horizontal])
            ax.set_ylim(lo[1], hi[1])
            ax.set_aspect("equal")
            ax.grid(False)
            ax.set_title(f"{view} ({'x' if horizontal == 0 else 'z'}-y)")
        last = [kind for t, kind in events if t <= trace["t"][k] + 1e-9]
        fig.suptitle(f"{run.name}: t = {trace['t'][k]:.3f} s" + (f", after {last[-1]}" if last else ""))
        return []

    movie = animation.FuncAnimation(fig, draw, frames=frames, blit=False)
    try:
        with atomic_output(out_file) as temporary:
            try:
                movie.save(temporary, writer=animation.FFMpegWriter(fps=fps, bitrate=2000), dpi=style.DPI // 2)
            except subprocess.CalledProcessError as e:
                raise OSError(ffmpeg_failure(e)) from e
    finally:
        plt.close(fig)
    return out_file
