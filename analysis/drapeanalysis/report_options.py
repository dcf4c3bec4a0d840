"""report.py's command line (docs/analysis.md, "Bad input"): its options, the range of each
number, and the checks of the options against the experiment. Every refusal is a ValueError or
an argparse error naming the option, exit status 2, before the report writes anything."""
import argparse
import os
from pathlib import Path

from . import runfiles
from .fileio import input_problem

# An animation needs two frames to move. More than 100000 (over an hour at 25 frames a second,
# several hours to draw) is a slip of the finger, not a wish.
FRAMES_RANGE = (2, 100_000)
FRAMES_DEFAULT = 300


def whole_number(low, high):
    """An argparse type: an integer from low to high (no fraction, nan or inf)."""
    def parse(text):
        try:
            value = int(text)
        except ValueError:
            value = None
        if value is None or not low <= value <= high:
            raise argparse.ArgumentTypeError(f"expected a whole number from {low} to {high}, got {text!r}")
        return value
    return parse


def folder_path(text):
    """An argparse type: a path that is not empty (Path("") would be the current folder)."""
    if not text:
        raise argparse.ArgumentTypeError("an empty path (give the experiment's folder)")
    return Path(text)


def parser(description):
    """The command line of report.py."""
    parser = argparse.ArgumentParser(description=description,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("directory", type=folder_path)
    parser.add_argument("--drapelab", metavar="PATH",
                        help="the drapelab program that writes the 3-D viewer pages (`drapelab report` passes itself)")
    parser.add_argument("--animate", nargs="*", metavar="RUN_ID",
                        help="also write an MP4 of these runs (every run with a trace.csv when no id is given); "
                             "needs ffmpeg")
    low, high = FRAMES_RANGE
    parser.add_argument("--frames", type=whole_number(low, high), metavar="N",
                        help=f"at most N frames an animation, {low} to {high} (default {FRAMES_DEFAULT}); "
                             "with --animate")
    return parser


def parse(description, argv=None):
    """The parsed options; argparse exits with status 2 on an option out of its range, and a
    --frames without --animate (it would change nothing) is refused the same way."""
    options = parser(description)
    args = options.parse_args(argv)
    if args.frames is not None and args.animate is None:
        options.error("--frames: only with --animate (it sets the animations' length)")
    if args.frames is None:
        args.frames = FRAMES_DEFAULT
    return args


def check_drapelab(path):
    """A ValueError naming --drapelab unless PATH is a program this user may run."""
    problem = input_problem(path)
    if problem is None and not os.access(path, os.X_OK):
        problem = "not executable"
    if problem:
        raise ValueError(f"--drapelab {path}: {problem}")


def animated_runs(directory, rows, ids):
    """The rows --animate names, or every finished row with a trace.csv when it names none; a
    ValueError for an id that is no run of the experiment, a named run without a trace.csv or
    summary.json (the animation draws the grid it gives), or no run to animate at all: each
    would leave the asked-for movie silently out."""
    unknown = [i for i in dict.fromkeys(ids) if i not in {row["id"] for row in rows}]
    if unknown:
        raise ValueError(f"--animate: no run {', '.join(unknown)} in {Path(directory) / 'results.json'}")
    traced = [row for row in rows if all((runfiles.run_dir(directory, row) / name).exists()
                                         for name in ("trace.csv", "summary.json"))]
    untraced = [i for i in dict.fromkeys(ids) if i not in {row["id"] for row in traced}]
    if untraced:
        raise ValueError(f"--animate: run {', '.join(untraced)} has no trace.csv "
                         "(output.trace_interval = 0) or no summary.json (it did not finish)")
    chosen = [row for row in traced if not ids or row["id"] in ids]
    if not chosen:
        raise ValueError("--animate: no run has a trace.csv (output.trace_interval = 0)")
    return chosen
