#!/usr/bin/env python3
"""`drapelab report` end to end on a tiny real experiment (docs/analysis.md, Viewer pages):
the report links a viewer page for every run with a trace and the scene's side-by-side page,
says why the run without a trace has none, shows the provenance of results.csv, and every
link it makes points at a written page that `drapelab view` made. With chromium installed the
report is also rendered (the screenshot is left in WORK_DIR for a person to look at).

Usage: report_viewer_check.py DRAPELAB SOURCE_DIR WORK_DIR
"""
import csv
import json
import re
import shutil
import subprocess
import sys
from pathlib import Path


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def run(command):
    result = subprocess.run([str(c) for c in command], capture_output=True, text=True, timeout=600)
    if result.returncode:
        fail(f"{' '.join(map(str, command))}: exit {result.returncode}\n{result.stdout}{result.stderr}")
    return result


def main():
    drapelab, source, work = sys.argv[1], Path(sys.argv[2]), Path(sys.argv[3])
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    # fig2_hold for 0.5 s: leap-frog and implicit Euler with a trace, leap-frog at a coarser
    # step without one, and leap-frog at a step that diverges within 0.01 s, with a trace and an
    # event trace: the report takes what a diverged run writes (its values stop at its last
    # finite step), though it refuses inf and times out of order in a run's files.
    scene = source / "experiments" / "scenes" / "fig2_hold.json"
    (work / "tiny.json").write_text(json.dumps({
        "name": "tiny", "question": "Does the report link the runs in 3-D?", "scenes": [str(scene)],
        "duration": 0.5, "set": {"output.energy_interval": 0.01},
        "cases": [{"integrator.name": "leapfrog", "integrator.dt": 0.0002, "output.trace_interval": 0.05},
                  {"integrator.name": "implicit-euler", "integrator.dt": 0.002, "output.trace_interval": 0.05},
                  {"integrator.name": "leapfrog", "integrator.dt": 0.0005, "output.trace_interval": 0},
                  {"integrator.name": "leapfrog", "integrator.dt": 0.003, "output.trace_interval": 0.05,
                   "output.event_trace_interval": 0.001}]}))
    out = work / "out"
    run([drapelab, "experiment", work / "tiny.json", "--out", out, "-j", "2"])
    run([drapelab, "report", out])
    with open(out / "results.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    page = (out / "report" / "report.html").read_text()
    if [r["status"] for r in rows].count("diverged") != 1:
        fail(f"expected one diverged run, got statuses {[r['status'] for r in rows]}")

    for key in ("version", "git_commit", "build_type", "sundials_version", "date", "machine.hostname"):
        if not rows[0].get(key):
            fail(f"results.csv has no {key}")
    for value in (rows[0]["version"], rows[0]["git_commit"], rows[0]["sundials_version"],
                  rows[0]["machine.hostname"], rows[0]["build_type"]):
        if f"<td>{value}</td>" not in page:
            fail(f"report.html does not show the provenance value {value}")

    links = re.findall(r"href='(view/[^']+)'", page)
    for link in links:
        target = out / "report" / link
        if not target.is_file() or 'id="drape-data"' not in target.read_text():
            fail(f"{link}: no viewer page")
    by_trace = {r["id"]: r["output.trace_interval"] != "0" for r in rows}
    for run_id, traced in by_trace.items():
        if (f"view/{run_id}.html" in links) != traced:
            fail(f"{run_id}: a page link {'missing' if traced else 'without a trace'}")
    untraced = next(r for r, traced in by_trace.items() if not traced)
    if f"<td>{untraced}</td><td>no page: no trace.csv (output.trace_interval = 0)</td>" not in page:
        fail("the run without a trace has no note why")
    side = "view/scenes/fig2_hold.html"
    if side not in links:
        fail("no side-by-side page of the scene")
    names = re.findall(r'"name":\s*"([^"]+)"', (out / "report" / side).read_text())
    print(f"OK: {len(set(links))} viewer pages linked; side by side: {sorted(set(names))[:4]}")

    chromium = shutil.which("chromium")
    if chromium:
        shot = work / "report.png"
        run([chromium, "--headless=new", "--no-sandbox", "--hide-scrollbars", "--window-size=1200,2000",
             "--host-resolver-rules=MAP * ~NOTFOUND", f"--screenshot={shot}", (out / "report" / "report.html").as_uri()])
        print(f"screenshot: {shot}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
