"""One style for every figure of the report (docs/analysis.md, Figures): text of at least 8 pt,
one colour per integrator, one line style and marker per step size, legends beside the axes,
event labels staggered, empty panels saying why, and each figure as PNG (200 dpi), SVG and PDF."""
import warnings

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

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
# Line styles and markers in order: the k-th step size of an integrator (or k-th variant).
LINE_STYLES = ("-", "--", ":", "-.", (0, (5, 1, 1, 1, 1, 1)), (0, (1, 3)))
MARKERS = ("o", "s", "^", "v", "D", "P", "X", "*")


def integrator_color(row, default=None):
    """The colour of a run's integrator (default for unknown names)."""
    return INTEGRATOR_COLORS.get(row.get("integrator.name") or row.get("integrator"), default)


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
    """Dotted vertical lines at (t, label) events; labels at staggered heights (inside the top
    of the axes, stepping down a level per event and wrapping) so neighbours do not overlap."""
    for k, (t, text) in enumerate(sorted(events)):
        ax.axvline(t, c="0.45", lw=0.7, ls=":")
        ax.text(t, 0.97 - 0.09 * (k % levels), " " + text, transform=ax.get_xaxis_transform(),
                fontsize=MIN_FONT, va="top", ha="left", color="0.25",
                bbox=dict(boxstyle="square,pad=0.1", fc="white", ec="none", alpha=0.7))


def empty_note(ax, why):
    """An empty panel that says why it is empty."""
    ax.text(0.5, 0.5, why, transform=ax.transAxes, ha="center", va="center", fontsize=MIN_FONT,
            color="0.3", wrap=True)
    ax.set_xticks([])
    ax.set_yticks([])
    ax.grid(False)


def save(fig, out_dir, stem):
    """Writes the figure as PNG (200 dpi), SVG and PDF and closes it; returns the stem."""
    with warnings.catch_warnings():  # figures with outside legends cannot always be tightened
        warnings.simplefilter("ignore")
        fig.tight_layout()
    for fmt in FORMATS:
        fig.savefig(out_dir / f"{stem}.{fmt}", dpi=DPI, bbox_inches="tight")
    plt.close(fig)
    return stem
