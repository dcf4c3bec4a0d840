"""Shaded front and side views of the cloth on the object, methods side by side at the same
instants (docs/analysis.md, Figures). Orthographic views drawn with the painter's algorithm:
the cloth's grid cells and the object's surface (its rings of object particles, dummy.csv) are
quads, sorted far to near and shaded by |n . l| (two-sided) for a light above the viewer."""
import math

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.collections import PolyCollection

from . import runfiles, style
from .run_series import read_run_series

MAX_METHODS = 7
MAX_INSTANTS = 6
CLOTH_RGB = np.array([0.27, 0.51, 0.71])
OBJECT_RGB = np.array([0.80, 0.80, 0.78])
# view: (horizontal axis, depth axis, depth sign: +1 when larger depth is nearer the viewer).
VIEWS = {"front": (0, 2, 1.0), "side": (2, 0, -1.0)}


def cloth_quads(x, rows, cols):
    """The grid cells of a rows x cols cloth, x (rows*cols, 3) row-major: (Q, 4, 3)."""
    grid = x.reshape(rows, cols, 3)
    return np.stack([grid[:-1, :-1], grid[:-1, 1:], grid[1:, 1:], grid[1:, :-1]], axis=2).reshape(-1, 4, 3)


def object_quads(dummy):
    """The object's surface from dummy.csv when its sections are rings of one size (the
    dress form, cylinders): quads between neighbouring points of neighbouring sections; None
    otherwise (the object is then drawn as points)."""
    sizes = dummy.groupby("section").size()
    if len(sizes) < 2 or sizes.nunique() != 1 or sizes.iloc[0] < 3:
        return None
    p = runfiles.positions(dummy.sort_values(["section", "point"])).reshape(len(sizes), sizes.iloc[0], 3)
    q = np.roll(p, -1, axis=1)
    return np.stack([p[:-1], q[:-1], q[1:], p[1:]], axis=2).reshape(-1, 4, 3)


def object_surface(run):
    """A run's object from its dummy.csv as (quads, points): quads when its sections are rings
    of one size (object_quads), else its points; (None, None) without the file."""
    if not (run / "dummy.csv").exists():
        return None, None
    dummy = runfiles.read_dummy(run / "dummy.csv")
    quads = object_quads(dummy)
    return quads, runfiles.positions(dummy) if quads is None else None


def cloth_grid(run, summary, trace):
    """(rows, cols) of a run's cloth (summary.json's scene), checked against its trace frames: a
    ValueError naming both files when rows x cols is not the particles of a frame, which the
    drawing's grid of cells would otherwise fail on with numpy's words."""
    rows, cols = (runfiles.scene_value(summary, f"cloth.{k}", None) for k in ("rows", "cols"))
    particles = trace["x"].shape[1]
    whole = all(isinstance(n, int) and not isinstance(n, bool) and n > 0 for n in (rows, cols))
    if not whole or rows * cols != particles:
        raise ValueError(f"{run / 'summary.json'}: scene.cloth.rows x cols = {rows} x {cols}, but "
                         f"{run / 'trace.csv'} has {particles} particles a frame")
    return rows, cols


def shade(quads, rgb, view):
    """Face colours: rgb times 0.35 + 0.65 |n . l|, n the cell normal (cross of its diagonals),
    l from the viewer, up and to the left."""
    horizontal, depth, sign = VIEWS[view]
    light = np.zeros(3)
    light[depth], light[1], light[horizontal] = sign, 0.6, -0.3
    light /= np.linalg.norm(light)
    normal = np.cross(quads[:, 2] - quads[:, 0], quads[:, 3] - quads[:, 1])
    length = np.linalg.norm(normal, axis=1)
    cosine = np.abs(normal @ light) / np.where(length > 0, length, 1.0)
    return np.clip((0.35 + 0.65 * cosine)[:, None] * rgb, 0, 1)


def draw_view(ax, view, cloth, colors, objects=None, object_points=None, fixed_points=None):
    """Cloth and object quads painted far to near in the given view; points on top."""
    horizontal, depth, sign = VIEWS[view]
    polys, faces = [cloth], [colors]
    if objects is not None:
        polys.append(objects)
        faces.append(shade(objects, OBJECT_RGB, view))
    polys, faces = np.concatenate(polys), np.concatenate(faces)
    order = np.argsort(sign * polys[:, :, depth].mean(axis=1))
    ax.add_collection(PolyCollection(polys[order][:, :, [horizontal, 1]], facecolors=faces[order],
                                     edgecolors=faces[order], linewidths=0.2,
                                     rasterized=True))  # SVG and PDF: text vector, mesh a 200 dpi image
    if object_points is not None:
        ax.scatter(object_points[:, horizontal], object_points[:, 1], s=0.5, c="0.7", zorder=0, rasterized=True)
    if fixed_points is not None and len(fixed_points):
        ax.scatter(fixed_points[:, horizontal], fixed_points[:, 1], s=10, c="tab:red", zorder=3)


def instants(summary, end):
    """The instants shown, as (kind, occurrence, t): every manipulation (not `ignored`) and the
    end, at most MAX_INSTANTS."""
    shown = [(kind, k, t) for kind, k, t in event_list(summary)][:MAX_INSTANTS - 1]
    return shown + [("end", 0, end)]


def event_list(summary):
    """(type, occurrence of that type, t) of a run's manipulations, in order."""
    counts, out = {}, []
    for e in summary.get("events", []):
        if e.get("type") != "ignored":
            k = counts[e["type"]] = counts.get(e["type"], -1) + 1
            out.append((e["type"], k, float(e["t"])))
    return out


def frame_at(trace, t):
    """The index of the last frame at or before t (the event frame at an event's time), None
    when the trace ends before t."""
    k = int(np.searchsorted(trace["t"], t + 1e-9, side="right")) - 1
    return k if k >= 0 and trace["t"][-1] >= t - 1e-9 else None


def run_frame(trace, summary, kind, occurrence):
    """The frame of an instant in one run: right after the run's own event of that type and
    occurrence (methods reach an event at slightly different times); None when the trace ends
    before it. Raises KeyError for a run without that event: another run's time would show
    another instant under the event's name."""
    if kind == "end":
        return len(trace["t"]) - 1
    own = {(k, n): time for k, n, time in event_list(summary)}
    return frame_at(trace, own[(kind, occurrence)])


def methods(rows):
    """The runs drawn for one scene: the reference first, then one per integrator (its
    smallest step), at most MAX_METHODS."""
    chosen, seen = [], set()
    order = list(style.INTEGRATOR_COLORS)
    for row in sorted(rows, key=lambda r: (not r.get("is_reference"), order.index(r["integrator"])
                                          if r.get("integrator") in order else len(order), _step(r))):
        name = "reference" if row.get("is_reference") else row.get("integrator")
        if name not in seen:
            seen.add(name)
            chosen.append(row)
    return chosen[:MAX_METHODS]


def _step(row):
    try:
        return float(row.get("integrator.dt", row.get("dt")))
    except (TypeError, ValueError):
        return math.inf


def method_name(row):
    """The column title of a run."""
    name = f"{row.get('integrator', '?')}\ndt={row.get('integrator.dt', row.get('dt'))}"
    return name + (" (ref.)" if row.get("is_reference") else "")


def scene_figures(directory, out_dir, scene, rows):
    """The front and side figures of one scene: a row per instant, a column per method."""
    runs = []
    for row in methods(rows):
        run = runfiles.run_dir(directory, row)
        # A run without summary.json did not finish (its trace may stop anywhere) and has no grid.
        if (run / "trace.csv").exists() and (run / "summary.json").exists():
            summary = runfiles.read_summary(run)
            trace = runfiles.trace_frames(read_run_series(run, summary, "trace.csv"))
            runs.append((row, summary, trace, cloth_grid(run, summary, trace)))
    if not runs:
        return []
    summary = runs[0][1]
    objects, points = object_surface(runfiles.run_dir(directory, runs[0][0]))
    shown = instants(summary, max(float(trace["t"][-1]) for _, _, trace, _ in runs))
    all_x = np.concatenate([trace["x"].reshape(-1, 3) for _, _, trace, _ in runs])
    lo, hi = all_x.min(axis=0) - 0.05, all_x.max(axis=0) + 0.05
    stems = []
    for view in VIEWS:
        horizontal = VIEWS[view][0]
        width = hi[horizontal] - lo[horizontal]
        panel_w = 1.9 * min(max(width / (hi[1] - lo[1]), 0.6), 1.4)
        fig, axes = plt.subplots(len(shown), len(runs), squeeze=False,
                                 figsize=(panel_w * len(runs) + 0.8, 2.0 * len(shown) + 0.6))
        for c, (row, run_summary, trace, (rows_n, cols_n)) in enumerate(runs):
            axes[0, c].set_title(method_name(row))
            for r, (kind, occurrence, _) in enumerate(shown):
                ax = axes[r, c]
                try:
                    k = run_frame(trace, run_summary, kind, occurrence)
                except KeyError:
                    style.empty_note(ax, f"no {kind.replace('_', ' ')}\nin this run")
                    continue
                if k is None:
                    style.empty_note(ax, f"no frame:\n{row.get('status', 'stopped')}\nat t={trace['t'][-1]:.3g} s")
                    continue
                x = trace["x"][k]
                cloth = cloth_quads(x, rows_n, cols_n)
                draw_view(ax, view, cloth, shade(cloth, CLOTH_RGB, view), objects, points, x[trace["fixed"][k]])
                ax.set_xlim(lo[horizontal], hi[horizontal])
                ax.set_ylim(lo[1], hi[1])
                ax.set_aspect("equal")
                ax.grid(False)
                ax.tick_params(labelleft=c == 0, labelbottom=r == len(shown) - 1)
                ax.text(0.02, 0.02, f"t={trace['t'][k]:.3f} s", transform=ax.transAxes, fontsize=style.MIN_FONT,
                        bbox=dict(fc="white", ec="none", alpha=0.7, pad=1))
            for r, (kind, _, _) in enumerate(shown):
                axes[r, 0].set_ylabel(f"{kind.replace('_', ' ')}\ny [m]")
        axis_name = "x" if horizontal == 0 else "z"
        for ax in axes[-1]:
            ax.set_xlabel(f"{axis_name} [m]")
        fig.suptitle(f"{scene}: {view} view ({axis_name}-y), cloth blue, fixed particles red")
        stems.append(style.save(fig, out_dir, f"snapshots_{scene}_{view}"))
    return stems
