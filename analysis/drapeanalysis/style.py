"""One style for every figure of the report (docs/analysis.md, Figures): text of at least 8 pt,
one colour per integrator, one line style and marker per step size, legends beside the axes,
event labels staggered, empty panels saying why, and each figure as PNG (200 dpi), SVG and PDF."""
import math
import warnings

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402
import matplotlib.transforms  # noqa: E402

from .fileio import atomic_output  # noqa: E402

MIN_FONT = 8
DPI = 200
FORMATS = ("png", "svg", "pdf")

RC = {
    "font.size": 9, "axes.titlesize": 9, "axes.labelsize": 9, "xtick.labelsize": MIN_FONT,
    "ytick.labelsize": MIN_FONT, "legend.fontsize": MIN_FONT, "figure.titlesize": 10,
    "lines.linewidth": 1.2, "lines.markersize": 4, "axes.grid": True, "grid.alpha": 0.3,
    "savefig.dpi": DPI, "svg.fonttype": "none", "pdf.fonttype": 42,
}
plt.rcParams.update(RC)

# One colour per integrator in every figure.
INTEGRATOR_COLORS = {"leapfrog": "tab:blue", "symplectic-euler": "tab:orange",
                     "implicit-euler": "tab:green", "arkode-erk": "tab:red",
                     "arkode-dirk": "tab:purple", "arkode-imex": "tab:brown"}
INTEGRATOR_MARKERS = {"leapfrog": "o", "symplectic-euler": "s", "implicit-euler": "^",
                      "arkode-erk": "v", "arkode-dirk": "D", "arkode-imex": "P"}
# Line styles and markers in order: the k-th step size of an integrator (or k-th variant).
LINE_STYLES = ("-", "--", ":", "-.", (0, (5, 1, 1, 1, 1, 1)), (0, (1, 3)))
MARKERS = ("o", "s", "^", "v", "D", "P", "X", "*")


# Log-axis error bars (log_errorbar): series k of n at the same x sit DODGE^(k - (n-1)/2) apart.
DODGE = 10 ** 0.015
# Half the width of an error bar's cap, in points (place_labels keeps labels clear of it).
CAP_SIZE = 3
# The foot of a bar whose interval reaches 0: an arrow glyph, unlike every integrator's marker.
ZERO_MARK = r"$\downarrow$"


def log_errorbar(ax, xs, ys, half, index=0, count=1, dodge=True, log_y=True, **kwargs):
    """ax.errorbar of means ys with 95 % half-widths. On a log y axis (`log_y`) a lower end at or
    below 0 cannot be drawn (matplotlib ran the bar to the panel's edge), so that bar stops at a
    tenth of its mean and ends in a down arrow, "reaches 0"; with `dodge`, series `index` of
    `count` is moved a little along a log x axis, so that bars of methods at the same step do not
    hide each other (the x values stay the steps' in the data, only the drawing moves)."""
    shift = DODGE ** (index - (count - 1) / 2) if dodge else 1.0
    xs = [x * shift for x in xs]
    half = [0.0 if h != h else h for h in half]  # nan (one run): no bar
    reaches_zero = [log_y and h >= y > 0 for y, h in zip(ys, half)]
    lower = [0.9 * y if zero else h for y, h, zero in zip(ys, half, reaches_zero)]
    bars = ax.errorbar(xs, ys, yerr=[lower, half], capsize=CAP_SIZE, **kwargs)
    color = bars.lines[0].get_color()
    ends = [(x, 0.1 * y) for x, y, zero in zip(xs, ys, reaches_zero) if zero]
    if ends:
        ax.plot(*zip(*ends), ls="none", marker=ZERO_MARK, color=color, ms=9)
    return bars


def log_x_ticks_at(ax, values):
    """A log x axis with its ticks and labels at `values` only: a decade's ticks left a horizon
    such as 0.0333 s unlabelled between 0.01 and 0.1."""
    ax.set_xscale("log")
    ax.xaxis.set_major_locator(matplotlib.ticker.FixedLocator(values))
    ax.xaxis.set_major_formatter(matplotlib.ticker.FuncFormatter(lambda v, _: f"{v:.3g}"))
    ax.xaxis.set_minor_locator(matplotlib.ticker.NullLocator())


# Integrators beyond the six above (xpbd, vbd, ...) take the next colours of tab10, then tab20's
# lighter halves, and markers none of the six uses, in the order they are declared:
# declare_integrators with `drapelab integrators --json`'s registry order (report.py), else in
# the order a figure first asks for them. A name keeps its colour for the whole report.
EXTRA_COLORS = tuple(f"tab:{c}" for c in ("pink", "gray", "olive", "cyan")) + tuple(
    matplotlib.colormaps["tab20"].colors[1::2])
EXTRA_MARKERS = ("X", "*", "h", "p", "<", ">", "d", "8")
KNOWN_INTEGRATORS = len(INTEGRATOR_COLORS)


def declare_integrators(names):
    """Gives each name of `names` not yet known the next free colour and marker, in order."""
    for name in names:
        if name not in INTEGRATOR_COLORS:
            k = len(INTEGRATOR_COLORS) - KNOWN_INTEGRATORS
            INTEGRATOR_COLORS[name] = EXTRA_COLORS[k % len(EXTRA_COLORS)]
            INTEGRATOR_MARKERS[name] = EXTRA_MARKERS[k % len(EXTRA_MARKERS)]


def _integrator_name(row):
    return row.get("integrator.name") or row.get("integrator")


def integrator_color(row, default=None):
    """The colour of a run's integrator: its own, declared on first use when new (default when
    the row names none)."""
    name = _integrator_name(row)
    if not name:
        return default
    declare_integrators([name])
    return INTEGRATOR_COLORS[name]


def integrator_marker(row):
    """The marker of a run's integrator (declared on first use, as integrator_color)."""
    name = _integrator_name(row)
    if not name:
        return "o"
    declare_integrators([name])
    return INTEGRATOR_MARKERS[name]


def variant_style(k):
    """Line style and marker of the k-th variant (step size) of a series: no two alike for
    k < 6."""
    return {"ls": LINE_STYLES[k % len(LINE_STYLES)], "marker": MARKERS[k % len(MARKERS)]}


def legend_beside(ax, **kwargs):
    """The legend outside the axes, to their right, so it never hides data."""
    handles, labels = ax.get_legend_handles_labels()
    if handles:
        ax.legend(handles, labels, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0,
                  frameon=False, **kwargs)


def legend_below(fig, axes, ncol=3):
    """One legend for the figure, under its panels (labels gathered from `axes`, no repeats)."""
    seen = {}
    for ax in axes:
        for handle, text in zip(*ax.get_legend_handles_labels()):
            seen.setdefault(text, handle)
    if seen:
        fig.legend(list(seen.values()), list(seen), loc="upper center", bbox_to_anchor=(0.5, 0.0),
                   ncol=ncol, frameon=False)


def mark_events(ax, events, levels=3):
    """Dotted vertical lines at (t, label) events, labelled above the axes (never over the
    data): a label starts a level higher than its left neighbour when they would overlap, and
    the title moves up to clear the levels used. Call after setting the title and x limits."""
    placed = []  # (level, right end in axes fraction)
    x0, x1 = ax.get_xlim()
    width = ax.get_window_extent().width or 400
    for t, text in sorted(events):
        ax.axvline(t, c="0.45", lw=0.7, ls=":")
        left = (t - x0) / (x1 - x0)
        # Text width in axes fraction: about 0.6 em a character at MIN_FONT points, 200 dpi.
        right = left + (len(text) + 1) * 0.6 * MIN_FONT * ax.figure.dpi / 72 / width
        level = next((k for k in range(levels) if all(r < left or lv != k for lv, r in placed)),
                     len(placed) % levels)
        placed.append((level, right))
        ax.text(t, 1.01 + 0.075 * level, text, transform=ax.get_xaxis_transform(), fontsize=MIN_FONT,
                va="bottom", ha="left", color="0.25", clip_on=False)
    if placed:
        used = 1 + max(level for level, _ in placed)
        ax.set_title(ax.get_title(), pad=4 + used * MIN_FONT * 1.4)


def _overlap(a, b):
    """Overlap area of two boxes (x0, y0, x1, y1)."""
    return max(0.0, min(a[2], b[2]) - max(a[0], b[0])) * max(0.0, min(a[3], b[3]) - max(a[1], b[1]))


# The gid of place_labels' own annotations, which it keeps as boxes of its own.
PLACED_LABEL = "drape_placed_label"


def place_labels(ax, points, texts, color, half=None, joined=False):
    """Annotates data points with short texts, each in the spot around its point (right, left,
    above, below, the corners) whose box overlaps least the labels, points and error bars already
    placed, so neighbouring labels do not overlap and no label covers a bar (`half`: the points'
    95 % half-widths, drawn by log_errorbar, whose bar stops at a tenth of y when it reaches 0;
    `joined`: the points are joined by a line in their order, which a label must not cover either).
    Call after the axes' scales and limits are final."""
    ax.autoscale_view()
    px_per_pt = ax.figure.dpi / 72
    char, height, gap = 0.62 * MIN_FONT * px_per_pt, 1.2 * MIN_FONT * px_per_pt, 3 * px_per_pt
    if not hasattr(ax, "_drape_boxes"):
        ax._drape_boxes = []
    boxes = ax._drape_boxes
    # Texts other drawers put on the axes (mark_partial's "n of N", mark_failed's notes) are
    # obstacles too; this function's own labels are in `boxes` already.
    renderer = ax.figure.canvas.get_renderer()
    others = [tuple(t.get_window_extent(renderer).extents) for t in ax.texts
              if t.get_gid() != PLACED_LABEL and t.get_text()]
    screen = [tuple(ax.transData.transform(p)) for p in points]
    boxes += [(x - gap, y - gap, x + gap, y + gap) for x, y in screen]
    cap = CAP_SIZE * px_per_pt
    for (x, y), h in zip(points, half or []):
        if h == h and h > 0:  # nan: one run, no bar
            # The caps are CAP_SIZE wide each side; a label at the bar's width touched them.
            (left, low), (_, high) = ax.transData.transform([(x, max(y - h, 0.1 * y)), (x, y + h)])
            boxes.append((left - cap - gap, low - gap, left + cap + gap, high + gap))
    if joined:  # the line between neighbours, as boxes a gap wide every gap along it
        for (x0, y0), (x1, y1) in zip(screen, screen[1:]):
            n = max(1, int(math.hypot(x1 - x0, y1 - y0) / gap))
            along = [(x0 + (x1 - x0) * k / n, y0 + (y1 - y0) * k / n) for k in range(n + 1)]
            boxes += [(x - gap, y - gap, x + gap, y + gap) for x, y in along]
    frame = ax.get_window_extent().extents  # a label outside the axes would cover the ticks

    def cost(box):
        return sum(_overlap(box, b) for b in boxes + others) + 4 * ((box[2] - box[0]) * (box[3] - box[1]) - _overlap(box, frame))

    for (x, y), (px, py), text in zip(points, screen, texts):
        w = char * len(text)
        # The corners sit a cap's half-width further out, so that one beside a bar clears its caps.
        side = gap + (cap if half else 0)
        # Rings of spots, each a label's height further out (the corners further up or down) and
        # chosen only where every nearer spot overlaps something, so that a neighbour's bar never
        # crosses a label placed beside it.
        spots = []  # (ring, dx, dy)
        for ring, far in enumerate((0.0, height, 2 * height)):
            spots += [(ring, gap + far, -height / 2), (ring, -gap - w - far, -height / 2)]
            spots += [(ring, dx, dy) for dy in (gap + far, -gap - height - far)
                      for dx in (-w / 2, side, -side - w)]
        _, dx, dy = min(spots, key=lambda s: s[0] + cost((px + s[1], py + s[2], px + s[1] + w,
                                                          py + s[2] + height)))
        boxes.append((px + dx, py + dy, px + dx + w, py + dy + height))
        # In points, as the text is: offsets in pixels stayed the screen's at the PNG's 200 dpi
        # while the text doubled, and labels placed apart overlapped.
        ax.annotate(text, (x, y), xytext=(dx / px_per_pt, dy / px_per_pt), textcoords="offset points",
                    fontsize=MIN_FONT, color=color, va="bottom", ha="left", gid=PLACED_LABEL)


def mark_partial(ax, points, color="k"):
    """Writes "n of N" beside each point of figure_data.with_intervals that stands for fewer runs
    than its ensemble had (the others diverged or wrote no value), so that a point from one of
    two runs does not read as the ensemble's."""
    for x, y, _, n, runs in points:
        if n < runs:
            ax.annotate(f"{n} of {runs}", (x, y), textcoords="offset points", xytext=(4, 4),
                        fontsize=MIN_FONT, color=color)


# A step with no value at all (every run diverged): an x on the axis' floor, not a missing step.
FAILED_MARK = "x"


def mark_failed(ax, failures, color, index=0, count=1):
    """An x at the bottom of the axes at each (x, text) of `failures` ("diverged (2 of 2)"),
    its text above it, series `index` of `count` dodged as log_errorbar does and its text a line
    higher, so that a step where a method failed stays on the axis and says so. A series' k-th
    failure's text goes k * count lines higher still: two failures of one series side by side
    would write over each other."""
    if not failures:
        return
    shift = DODGE ** (index - (count - 1) / 2)
    floor = matplotlib.transforms.blended_transform_factory(ax.transData, ax.transAxes)
    xs = [x * shift for x, _ in failures]
    ax.plot(xs, [0.03] * len(xs), ls="none", marker=FAILED_MARK, ms=7, mew=1.5, color=color,
            transform=floor, clip_on=False)
    for k, (x, text) in enumerate(zip(xs, (text for _, text in failures))):
        ax.text(x, 0.07 + 0.07 * (index + k * count), text, transform=floor, fontsize=MIN_FONT,
                color=color, ha="center", va="bottom")


def label_log_ticks(ax):
    """Gives each log axis of `ax` at least two labelled ticks: a range within a decade or two
    would show one label, so the ticks go to 1, 2 and 5
    times the decades, or to every integer multiple, all labelled (matplotlib itself falls back to
    evenly spaced ticks when even those leave one inside)."""
    for axis, limits in ((ax.xaxis, ax.get_xlim()), (ax.yaxis, ax.get_ylim())):
        # An axis with no positive limit (nothing drawn on it) has no decades to label.
        if (axis.get_scale() != "log" or min(limits) <= 0
                or len(labelled_ticks(axis, *sorted(limits))) >= 2):
            continue
        axis.set_major_formatter(matplotlib.ticker.LogFormatterSciNotation(
            labelOnlyBase=False, minor_thresholds=(math.inf, math.inf)))
        for subs in ((1.0, 2.0, 5.0), tuple(range(1, 10))):
            axis.set_major_locator(matplotlib.ticker.LogLocator(subs=subs))
            if len(labelled_ticks(axis, *sorted(limits))) >= 2:
                break


def labelled_ticks(axis, low, high):
    """The major ticks of `axis` from low to high that its formatter gives a label."""
    ticks = [t for t in axis.get_major_locator()() if low <= t <= high]
    formatter = axis.get_major_formatter()
    formatter.set_locs(ticks)
    return [t for t in ticks if formatter(t)]


def empty_note(ax, why):
    """An empty panel that says why it is empty."""
    ax.text(0.5, 0.5, why, transform=ax.transAxes, ha="center", va="center", fontsize=MIN_FONT,
            color="0.3", wrap=True)
    ax.set_xticks([])
    ax.set_yticks([])
    ax.grid(False)


def save(fig, out_dir, stem):
    """Writes the figure as PNG (200 dpi), SVG and PDF, each whole or not at all
    (fileio.atomic_output), and closes it; returns the stem."""
    for ax in fig.axes:
        label_log_ticks(ax)
    with warnings.catch_warnings():  # figures with outside legends cannot always be tightened
        warnings.simplefilter("ignore")
        if fig.get_layout_engine() is None:  # a constrained figure (subfigures) lays itself out
            fig.tight_layout()
    try:
        for fmt in FORMATS:
            with atomic_output(out_dir / f"{stem}.{fmt}") as temporary:
                fig.savefig(temporary, format=fmt, dpi=DPI, bbox_inches="tight")
    finally:
        plt.close(fig)
    return stem
