#!/usr/bin/env python3
"""Metrics, plots and an HTML report of an experiment folder.

Usage: report.py DIR [--drapelab PATH] [--animate [RUN_ID ...]] [--frames N]
Reads DIR/results.json and the files of every run (docs/outputs.md); writes DIR/metrics.csv and
DIR/metrics.json (the results table plus the metrics of docs/analysis.md) and DIR/report/:
report.html with the runs' provenance, its figures as PNG, SVG and PDF, a method x scene
summary, 3-D viewer pages (report/view/, written with `PATH view`) and the full table.
`drapelab report DIR` runs this script and passes itself as --drapelab.
Exit status (as drapelab's): 0 done, 1 ffmpeg missing for --animate, 2 bad input (the message
names the file or the option), 4 an output could not be written (the message names it; no half
file is left, and report.html, written last, is not there).
"""
import concurrent.futures
import contextlib
import csv
import html
import itertools
import json
import math
import os
import sys
from collections import Counter

try:
    import pandas  # noqa: F401  (the summary and the metrics read run files with it)
except ImportError:  # drapelab report checks for matplotlib and numpy only
    sys.exit("report.py needs pandas (Debian: apt install python3-pandas; install_dependencies.sh installs it)")

from drapeanalysis import (metrics, plots, report_options, results_file, runfiles,  # noqa: E402
                           style, table_columns, viewer_pages)
from drapeanalysis.integrator_order import integrator_order  # noqa: E402
from drapeanalysis.report_summary import (SUMMARY_NOTE, attach_note, method_name, summary_tables,  # noqa: E402
                                          unfinished_banner)
from drapeanalysis.fileio import OutputError, atomic_output, check_writable_folder, output_folder  # noqa: E402
from drapeanalysis.figure_catalogue import CAPTIONS, figure_metrics  # noqa: E402

# The provenance fields of the results table (docs/outputs.md, Provenance) and their titles.
PROVENANCE = (("version", "drapelab version"), ("git_commit", "git commit"), ("build_type", "build type"),
              ("sundials_version", "SUNDIALS version"), ("machine.hostname", "machine"),
              ("machine.cpu", "CPU"), ("machine.cores", "cores"))


def add_metrics(directory, results):
    """Every row of the results table with the analysis metrics of its run added."""
    rows = results["runs"]
    by_id = {row["id"]: row for row in rows}
    out, windows = [], {}
    # Runs are independent and their metrics most of a report's time (reading and filtering the
    # event traces): one process a core; map keeps the plan's order, and a run's error (a broken
    # file, named) is raised here as it would be in a loop.
    with concurrent.futures.ProcessPoolExecutor(max_workers=min(os.cpu_count() or 1, len(rows) or 1)) as pool:
        computed = list(pool.map(metrics.run_metrics, itertools.repeat(directory), rows,
                                 itertools.repeat(by_id)))
    for row, (extra, run_windows) in zip(rows, computed):
        out.append({**row, **extra})
        if run_windows:
            windows[row["id"]] = run_windows
    return out, windows


def clean(value):
    """JSON has no nan: missing metrics become null."""
    return None if isinstance(value, float) and not math.isfinite(value) else value


def write_metrics(directory, results, rows, windows):
    """DIR/metrics.json and DIR/metrics.csv: the full table, one row per run."""
    columns = list(results["columns"])
    for row in rows:
        columns += [key for key in row if key not in columns]
    doc = {key: results[key] for key in ("name", "question", "metrics", "parameters", "plan_size")}
    doc.update(columns=columns, runs=[{k: clean(v) for k, v in row.items()} for row in rows],
               vibration_windows=windows)
    with atomic_output(directory / "metrics.json") as temporary, open(temporary, "w") as f:
        json.dump(doc, f, indent=1, default=clean)
    with atomic_output(directory / "metrics.csv") as temporary, open(temporary, "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(columns)
        for row in rows:
            writer.writerow(["" if clean(row.get(c)) is None else cell(row.get(c)) for c in columns])


def cell(value):
    """A CSV or HTML cell: JSON for lists and objects, repr precision for floats."""
    if isinstance(value, (list, dict)):
        return json.dumps(value)
    if isinstance(value, bool):
        return str(value).lower()
    return value


def provenance_html(rows):
    """Where the results come from: each provenance field's values over the runs (with their
    counts when merged shards ran on different builds or machines) and the runs' dates."""
    items = []
    for key, title in PROVENANCE:
        counts = Counter(str(cell(r[key])) for r in rows if clean(r.get(key)) not in (None, ""))
        text = "; ".join(v if len(counts) == 1 else f"{v} ({n} run{'s' * (n > 1)})" for v, n in counts.items())
        items.append((title, text or "not recorded"))
    dates = sorted(str(r["date"]) for r in rows if r.get("date"))
    items.append(("runs started", (dates[0] if dates[0] == dates[-1] else f"{dates[0]} to {dates[-1]}")
                  if dates else "not recorded"))
    body = "".join(f"<tr><th>{html.escape(t)}</th><td>{html.escape(v)}</td></tr>" for t, v in items)
    dirty = any(str(r.get("git_commit", "")).endswith("-dirty") for r in rows)
    return ("<h2>Provenance</h2><table class='provenance'>" + body + "</table>"
            + ("<p>-dirty: built from a tree with uncommitted changes.</p>" if dirty else ""))


def viewer_html(rows, parameters, pages):
    """The viewer section: per scene the side-by-side page and every run's page, and why the
    runs without a page have none."""
    if pages is None:
        return ("<h2>3-D viewer</h2><p>No viewer pages: report.py ran without --drapelab "
                "(<code>drapelab report DIR</code> passes it).</p>")
    links, notes, scenes = pages
    parts = ["<h2>3-D viewer</h2><p>Each page plays runs in 3-D in the browser, offline "
             "(<code>drapelab view</code>, docs/viewer.md): the cloth, the dress form, the hands, "
             "a time slider with the events and the energy under it.</p><ul>"]
    by_scene = {}
    for row in rows:
        by_scene.setdefault(plots.scene_name(row), []).append(row)
    for scene, scene_rows in by_scene.items():
        runs = ", ".join(f"<a href='{links[r['id']]}'>{html.escape(method_name(r, parameters))}</a>"
                         for r in scene_rows if r["id"] in links)
        item = f"<li><b>{html.escape(scene)}</b>: "
        if scene in scenes:
            page, chosen = scenes[scene]
            names = " | ".join(html.escape(method_name(r, parameters)) for r in chosen)
            item += f"<a href='{page}'>side by side: {names}</a>; "
        parts.append(item + (f"each run: {runs}" if runs else "no run has a page") + "</li>")
    parts.append("</ul>")
    reasons = Counter(notes.values())
    if reasons:
        parts.append("<p>Runs without a page: " + "; ".join(
            f"{n} run{'s' * (n > 1)}, {html.escape(reason.removeprefix('no page: '))}" for reason, n in reasons.items())
            + " (the runs table names them).</p>")
    return "".join(parts)


# What the runs table's cells mean (docs/analysis.md, "The report").
RUNS_NOTE = ("<p>Lengths in mm (metrics.csv keeps them in m), times in s. An empty cell: the metric "
             "does not apply to the run, or the run did not finish (its status, the simulated time it "
             "reached and why are beside it; a run that stopped has no energy drift either, as a drift "
             "over part of a run does not compare with a whole run's). \"k not fixed\": k attaches of "
             "the run were never fixed, so it has no attach error for them.</p>")


def html_table(rows, parameters, pages=None):
    """The results as an HTML table: id, its viewer page (or why none), parameters, the main
    metrics present."""
    present = [c for c in table_columns.TABLE_COLUMNS
               if any(clean(r.get(c)) not in (None, "") or attach_note(r, c) for r in rows)]
    columns = ["id"] + list(parameters) + present
    head = "".join(f"<th>{html.escape(table_columns.heading(c))}</th>"
                   for c in columns[:1] + ["3-D"] * (pages is not None) + columns[1:])
    body = []
    for row in rows:
        cells = []
        for c in columns:
            value = clean(row.get(c))
            text = ("" if value is None else f"{table_columns.shown_value(c, value):.4g}"
                    if isinstance(value, float) else str(cell(value)))
            # An empty attach error is a failed attach when one was never fixed, else none applies.
            note = attach_note(row, c)
            text = f"{text} ({note})" if text and note else text or note
            cells.append(f"<td>{html.escape(text)}</td>")
        if pages is not None:  # the page beside the id
            links, notes, _ = pages
            cells.insert(1, f"<td><a href='{links[row['id']]}'>view</a></td>" if row["id"] in links
                         else f"<td>{html.escape(notes.get(row['id'], ''))}</td>")
        body.append("<tr>" + "".join(cells) + "</tr>")
    return f"<div class='wide'><table><tr>{head}</tr>{''.join(body)}</table></div>"


# The keys of a field solver's work per step, the first a run sets: xpbd's substeps, projective
# dynamics' and vbd's iterations (xpbd's iterations a substep come second).
SOLVER_WORK = ("integrator.substeps", "integrator.iterations")


def solver_work(row):
    """The run's SOLVER_WORK value (nan for a method without one)."""
    return next((v for k in SOLVER_WORK if math.isfinite(v := plots.number(row.get(k)))), math.nan)


def make_figures(directory, out_dir, rows, parameters, shown=()):
    """Every figure the table supports and the experiment's `metrics` ask for (all when it names
    none), as (stem, caption)."""
    def wanted(metric):
        return not shown or metric in shown

    def settle_time(row):
        return plots.number(row.get("manipulation.attach_iterations")) * plots.number(row.get("dt"))

    # The attach figures: a field solver's runs that sweep its work per step (its "calculation
    # time") against that work, the others against their attach iterations.
    solver_runs = [row for row in rows if math.isfinite(solver_work(row))]
    stepped_runs = [row for row in rows if not math.isfinite(solver_work(row))]
    detail = plots.INTEGRATOR_DETAIL[1:]
    makers = [
        ("energy_vs_time", lambda: plots.energy_vs_time(directory, out_dir, rows, parameters)),
        ("energy_by_scene", lambda: plots.energy_by_scene(directory, out_dir, rows, parameters)),
        ("work_precision", lambda: plots.work_precision(out_dir, rows, parameters)),
        ("restart_error_vs_horizon", lambda: plots.restart_error_vs_horizon(directory, out_dir, rows, parameters)),
        ("attach_error_vs_iterations", lambda: plots.line_plot(
            out_dir, "attach_error_vs_iterations", stepped_runs, parameters, "manipulation.attach_iterations",
            "attach_error_mean", "attach iterations", "attach error [m]", exclude=detail)),
        ("attach_error_vs_solver_work", lambda: plots.line_plot(
            out_dir, "attach_error_vs_solver_work", solver_runs, parameters, solver_work, "attach_error_mean",
            "substeps or iterations a step", "attach error [m]",
            exclude=detail + SOLVER_WORK + ("integrator.dt", "manipulation.attach_iterations"))),
        ("attach_error_vs_time", lambda: plots.line_plot(
            out_dir, "attach_error_vs_time", stepped_runs, parameters, settle_time, "attach_error_mean",
            "attach_iterations x dt [s]", "attach error [m]",
            exclude=detail + ("manipulation.attach_iterations",))
         if "manipulation.attach_iterations" in parameters else None),
        ("vibration_vs_dt", lambda: plots.vibration_vs_dt(out_dir, rows, parameters)),
        ("vibration_events_vs_dt", lambda: plots.vibration_vs_dt(
            out_dir, rows, parameters, "vibration_rms_events", "vibration RMS, after events [m]",
            "vibration_events_vs_dt")),
        ("contact_switch_vs_dt", lambda: plots.vibration_vs_dt(
            out_dir, rows, parameters, "contact_switch_rate_final",
            "contact switches [1/(particle s)]", "contact_switch_vs_dt")),
        ("stable_dt", lambda: plots.stable_dt(out_dir, rows, parameters)),
        ("accuracy_cost", lambda: plots.accuracy_cost(out_dir, rows, parameters)),
    ]
    figures = [(name, make()) for name, make in makers if all(map(wanted, figure_metrics(name)))]
    out = [(stem, CAPTIONS[name]) for name, stem in figures if stem]
    if not wanted("snapshots"):
        return out
    out += [(stem, f"{stem.rsplit('_', 1)[-1].capitalize()} view of the cloth (blue, shaded) on the object "
                   "(grey) at every manipulation and at the end (rows), the reference and one run per "
                   "integrator, its smallest step (columns); fixed particles red.")
            for stem in plots.snapshots(directory, out_dir, rows)]
    return out


def write_html(out_dir, results, rows, figures, videos=(), pages=None):
    """report.html: the question, the provenance, the method x scene summary, the viewer pages
    (`pages` from viewer_pages.write_pages, None when not written), the figures (PNG, linked to
    SVG and PDF, snapshots to their scene's viewer page), animations, the full table folded away."""
    parts = [f"<h1>{html.escape(results['name'])}</h1>",
             f"<p><b>Question.</b> {html.escape(results.get('question') or '')}</p>",
             unfinished_banner(rows, results["parameters"]), provenance_html(rows)]
    scene_pages = pages[2] if pages else {}
    summary = summary_tables(rows, results["parameters"])
    if summary:
        parts.append("<h2>Summary</h2>" + SUMMARY_NOTE + summary)
    parts.append(viewer_html(rows, results["parameters"], pages))
    parts.append("<h2>Figures</h2>")
    for stem, caption in figures:
        scene = stem.removeprefix("snapshots_").rpartition("_")[0] if stem.startswith("snapshots_") else ""
        view = (f", <a href='{scene_pages[scene][0]}'>in 3-D</a>" if scene in scene_pages else "")
        parts.append(f'<figure><img src="{stem}.png" alt="{html.escape(stem)}">'
                     f"<figcaption>{html.escape(caption)} <a href='{stem}.svg'>SVG</a>, "
                     f"<a href='{stem}.pdf'>PDF</a>{view}</figcaption></figure>")
    for name in videos:
        parts.append(f"<figure><video controls src='{name}' width='640'></video>"
                     f"<figcaption>{html.escape(name)}</figcaption></figure>")
    parts.append("<h2>Runs</h2><details><summary>Every run with its parameters, viewer page and main "
                 f"metrics ({len(rows)} rows)</summary>" + RUNS_NOTE + html_table(rows, results["parameters"], pages)
                 + "</details>")
    parts.append("<p>Every parameter and metric: <a href='../metrics.csv'>metrics.csv</a>, "
                 "<a href='../metrics.json'>metrics.json</a>. Metrics: docs/analysis.md.</p>")
    # Prose keeps a readable measure; tables and figures take the window's width (the runs
    # table scrolls in its own box when wider).
    style = ("body{font-family:sans-serif;margin:2em}p,ul,figcaption{max-width:70em}img{max-width:100%}"
             "div.banner{border:2px solid #c00;background:#fff4f4;padding:0 1em;margin:1em 0}"
             "table{border-collapse:collapse;font-size:80%;margin-bottom:1em}"
             "td,th{border:1px solid #ccc;padding:2px 5px}table.summary td{text-align:right}"
             "figure{margin:1em 0}summary{cursor:pointer}"
             "table.provenance th{text-align:left;background:#f4f4f4}div.wide{overflow-x:auto}")
    page = (f"<!DOCTYPE html><html><head><meta charset='utf-8'><title>{html.escape(results['name'])}"
            f"</title><style>{style}</style></head><body>{''.join(parts)}</body></html>\n")
    with atomic_output(out_dir / "report.html") as temporary:
        temporary.write_text(page)


def animate(directory, out_dir, rows, frames):
    """An MP4 per row (report_options.animated_runs): the file names."""
    from drapeanalysis import animation  # needs ffmpeg only when asked for
    names = []
    for row in rows:
        names.append(f"{row['id']}.mp4")
        animation.animate_run(runfiles.run_dir(directory, row), out_dir / names[-1], max_frames=frames)
    return names


def remove_previous_report(out_dir):
    """The previous report.html goes before anything is read: should the experiment's files be
    malformed, a write fail, or a file only a figure reads be bad, the folder must not look
    finished (a report refused on bad input left the last report.html in place). A folder that
    is not there (or no folder) is left to the loader, which names it."""
    if not out_dir.parent.is_dir():
        return
    if out_dir.exists() and not out_dir.is_dir():
        raise ValueError(f"{out_dir}: not a folder (the report writes its files there)")
    try:
        with contextlib.suppress(FileNotFoundError):
            (out_dir / "report.html").unlink()
    except OSError as e:
        raise OutputError(f"cannot remove the previous {out_dir / 'report.html'}: {e.strerror}") from e


def write_report(args, results, rows, windows, animated):
    """metrics.csv, metrics.json and report/ with its figures, animations and viewer pages, and
    report.html last (remove_previous_report has removed the last one)."""
    out_dir = args.directory / "report"
    write_metrics(args.directory, results, rows, windows)
    output_folder(out_dir)
    style.declare_integrators(integrator_order(args.drapelab, rows))
    figures = make_figures(args.directory, out_dir, rows, results["parameters"], results.get("metrics") or ())
    videos = animate(args.directory, out_dir, animated, args.frames) if animated else []
    pages = (viewer_pages.write_pages(args.directory, out_dir, rows, args.drapelab)
             if args.drapelab else None)
    write_html(out_dir, results, rows, figures, videos, pages)
    return out_dir / "report.html"


def main():
    args = report_options.parse(__doc__)
    if args.animate is not None:
        from drapeanalysis import animation
        if not animation.available():
            # Not bad input but a missing program: exit 1, as `drapelab report` without matplotlib.
            sys.exit("report.py: error: --animate needs ffmpeg (Debian: apt install ffmpeg)")
    try:
        if args.drapelab is not None:
            report_options.check_drapelab(args.drapelab)
        if args.directory.is_dir():
            check_writable_folder(args.directory)
        remove_previous_report(args.directory / "report")
        results = results_file.load_complete_experiment(args.directory)
        animated = (report_options.animated_runs(args.directory, results["runs"], args.animate)
                    if args.animate is not None else [])
        rows, windows = add_metrics(args.directory, results)
        print(write_report(args, results, rows, windows, animated))
    except ValueError as e:
        # Bad input: the message names the file and the field, or the option; exit 2 as drapelab
        # does, without a traceback. A file only a figure reads (a run's dummy.csv) is found
        # while drawing.
        print(f"report.py: error: {e}", file=sys.stderr)
        sys.exit(2)
    except OutputError as e:
        # A failed write (a full disk, no permission, a file size limit): exit 4 as drapelab's.
        print(f"report.py: error: {e}", file=sys.stderr)
        sys.exit(4)


if __name__ == "__main__":
    main()
