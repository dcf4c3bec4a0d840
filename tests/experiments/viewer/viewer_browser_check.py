#!/usr/bin/env python3
"""`drapelab view` in a real browser (docs/viewer.md, Browser check).

Runs a tiny hold scene twice with a trace (leap-frog and implicit Euler), writes their page
with `drapelab view`, opens it in headless chromium with the page's test hook
(#test&t=A&t=B), and checks what the page wrote into its DOM: no errors, a picture in each
run's viewport, different pictures at the two times, that the slider, play and a camera
button act, that the run labels lie under the canvas, that a run with its final state only (no
trace) opens at its end, and that a diverged run is named in the banner with its reason and
opens at its last frame. Also checks that `drapelab view` refuses a folder that is not a run, and a
malformed trace, with exit status 2.

Usage: viewer_browser_check.py DRAPELAB SOURCE_DIR WORK_DIR   (exit 77: no chromium, skipped)
"""
import html
import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

# The flags that give WebGL in Debian 12's headless chromium without a GPU: ANGLE on
# SwiftShader (software rendering), which chromium only keeps using for WebGL when told it is
# fine. No host name resolves, so a page that needed the network would fail the check.
CHROMIUM_FLAGS = ["--headless=new", "--no-sandbox", "--use-angle=swiftshader",
                  "--enable-unsafe-swiftshader", "--hide-scrollbars", "--window-size=800,600",
                  "--host-resolver-rules=MAP * ~NOTFOUND"]
TIMES = (0.1, 0.7, 0.8)  # before and after the hold at about 0.4 s, and the end


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def run(command, expect=0):
    result = subprocess.run(command, capture_output=True, text=True, timeout=120)
    if result.returncode != expect:
        fail(f"{' '.join(map(str, command))}: exit {result.returncode}, expected {expect}\n"
             f"{result.stdout}{result.stderr}")
    return result


def find_chromium():
    for name in (os.environ.get("CHROMIUM"), "chromium", "chromium-browser", "google-chrome"):
        if name and shutil.which(name):
            return shutil.which(name)
    return None


def page_result(chromium, url, work, name, window="800,600"):
    """The page's #test-result (docs/viewer.md, Browser check) in a window of `window` pixels,
    failing on the errors it logged."""
    flags = [f"--window-size={window}" if flag.startswith("--window-size") else flag
             for flag in CHROMIUM_FLAGS]
    dom = run([chromium] + flags + ["--dump-dom", url]).stdout
    (work / f"{name}.dom.html").write_text(dom)
    found = re.search(r'<pre id="test-result"[^>]*>(.*?)</pre>', dom, re.S)
    errors = re.search(r'<div id="errors"[^>]*>(.*?)</div>', dom, re.S)
    if errors and errors.group(1).strip():
        fail(f"{name}: the page reported errors:\n" + html.unescape(errors.group(1)))
    if not found or not found.group(1).strip():
        fail(f"{name}: the page wrote no test result (see {work / name}.dom.html)")
    result = json.loads(html.unescape(found.group(1)))
    if not result.get("ok") or result.get("errors"):
        fail(f"{name}: the page's test hook failed: " + json.dumps(result)[:500])
    return result


def check_diverged(drapelab, chromium, scene, work):
    """Leap-frog at 2 ms on fig2_hold diverges at 0.008 s, before its first trace interval: the
    page names it in the banner with summary.json's reason and opens at its last frame, t = 0
    (it showed that flat cloth with no word in the banner; docs/viewer.md, Diverged runs)."""
    run([drapelab, "run", scene, "--out", work / "leapfrog_2ms", "--set", "duration=0.8",
         "--set", "output.trace_interval=0.0333333", "--set", "integrator.name=leapfrog",
         "--set", "integrator.dt=0.002"], expect=3)
    summary = json.loads((work / "leapfrog_2ms" / "summary.json").read_text())
    page = work / "diverged.html"
    run([drapelab, "view", work / "leapfrog_2ms", "--out", page])
    result = page_result(chromium, page.resolve().as_uri() + "#test", work, "diverged")
    expected = (f"leapfrog_2ms diverged at t = {summary['sim_time']:.3f} s: {summary['reason']}; "
                "last frame written at t = 0.000 s")
    if result["notice"] != expected or result["start"] != 0:
        fail(f"diverged run: banner {result['notice']!r}, opened at {result['start']}; "
             f"expected {expected!r} at 0")
    # Its one energy row (t = 0) is no line: the plot says so instead of standing empty.
    note = f"leapfrog_2ms: energy written at t = 0.000 s only (the run stopped at t = {summary['sim_time']:.3f} s)"
    if result["energy_notes"] != [note]:
        fail(f"diverged run: energy plot notes {result['energy_notes']!r}, expected {[note]!r}")
    # Beside a run that finished, in a short window: the banner, both labels, the plot and the
    # legend fit without scrolling (the legend sat 20-40 px below the fold at 1000 x 700).
    pair = work / "pair.html"
    run([drapelab, "view", work / "leapfrog", work / "leapfrog_2ms", "--out", pair])
    result = page_result(chromium, pair.resolve().as_uri() + "#test", work, "pair", "1000,700")
    layout = result["layout"]
    if not result["notice"] or layout["legend"]["bottom"] > layout["window_height"]:
        fail(f"1000 x 700 with a banner: legend below the fold: {json.dumps(layout)}")


def main():
    drapelab, source, work = sys.argv[1], Path(sys.argv[2]), Path(sys.argv[3])
    chromium = find_chromium()
    if not chromium:
        print("SKIP: no chromium (Debian: apt install chromium; install_dependencies.sh does)")
        return 77
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    scene = source / "experiments" / "scenes" / "fig2_hold.json"
    # The interval does not divide the duration: the last frame is at 0.7999992 s, before the end.
    common = ["--set", "duration=0.8", "--set", "output.trace_interval=0.0333333"]
    run([drapelab, "run", scene, "--out", work / "leapfrog"] + common)
    # A name as long as an experiment's run ids: the legend beside the energy buttons wraps.
    implicit = work / "fig2_hold-dt0.002-implicit-euler-a-name-as-long-as-a-run-id-seed1-0123abcd"
    run([drapelab, "run", scene, "--out", implicit] + common +
        ["--set", "integrator.name=implicit-euler", "--set", "integrator.dt=0.002"])

    # Not a run, and a malformed trace: exit 2, the message names the folder / the file.
    message = run([drapelab, "view", work, "--out", work / "x.html"], expect=2).stderr
    if f"{work}: not a run folder" not in message:
        fail("not a run: message does not name the folder: " + message)
    shutil.copytree(work / "leapfrog", work / "broken")
    trace = (work / "broken" / "trace.csv").read_text().splitlines()
    trace[5] = trace[5].replace(",", ",x", 1)
    (work / "broken" / "trace.csv").write_text("\n".join(trace) + "\n")
    message = run([drapelab, "view", work / "broken", "--out", work / "x.html"], expect=2).stderr
    if f"{work / 'broken' / 'trace.csv'}: line 6: column 'index' is not a number" not in message:
        fail("malformed trace: message does not name the file and line: " + message)

    page = work / "page.html"
    run([drapelab, "view", work / "leapfrog", implicit, "--out", page])
    url = page.resolve().as_uri() + "#test&" + "&".join(f"t={t}" for t in TIMES)
    result = page_result(chromium, url, work, "page")
    print(json.dumps(result))
    # The labels lie under the canvas, not over the cloth, and no banner for runs that are ok.
    canvas, labels = result["layout"]["canvas"], result["layout"]["labels"]
    if labels["top"] < canvas["bottom"] - 0.5 or result["notice"] or result["energy_notes"]:
        fail(f"labels over the canvas, or a banner or an energy note for ok runs: "
             f"{json.dumps(result['layout'])}, {result['notice']!r}, {result['energy_notes']!r}")
    pixels = result["width"] * result["height"]
    renders = result["renders"]
    for r in renders:
        if r["nonbackground"] < 0.02 * pixels:
            fail(f"t = {r['t']}: canvas nearly blank ({r['nonbackground']} of {pixels} pixels)")
        for name, count in zip((x["name"] for x in result["runs"]), r["per_view"]):
            if count < 0.01 * pixels:
                fail(f"t = {r['t']}: the viewport of {name} is nearly blank ({count} pixels)")
    if renders[0]["checksum"] == renders[1]["checksum"]:
        fail(f"the pictures at t = {TIMES[0]} and {TIMES[1]} are the same")
    # Both runs end at 0.8 s: neither has ended at the end (it read "run ended" past the last
    # frame, which a trace interval that does not divide the duration leaves before the end).
    if any("run ended" in label for label in renders[-1]["labels"]):
        fail(f"t = {TIMES[-1]}: a run reads as ended at its own end: {renders[-1]['labels']}")
    ui = result["ui"]
    if abs(ui["slider_t"] - 0.2) > 1e-9 or abs(ui["played"] - 0.5) > 1e-9 or ui["camera"] != "side":
        fail("the slider, play or camera buttons do not work: " + json.dumps(ui))
    # No button's label wraps at 800 px ("total - E(0)" did, on three lines, beside a legend of
    # run ids).
    lines = ui.get("button_lines", {})
    if len(lines) < 6 or set(lines.values()) != {1}:
        fail("a button's label is not on one line (lines a button): " + json.dumps(lines))
    # A run with its final state only (no trace.csv) opens at its end, where that state is: it
    # opened at t = 0, the final cloth beside the hands of t = 0.
    run([drapelab, "run", scene, "--out", work / "final_only", "--set", "duration=0.8",
         "--set", "output.trace_interval=0"])
    final_page = work / "final_only.html"
    run([drapelab, "view", work / "final_only", "--out", final_page])
    final = page_result(chromium, final_page.resolve().as_uri() + "#test", work, "final_only")
    opened_at = [r["t"] for r in final.get("renders", [])]
    if opened_at != [0.8]:
        fail("a run with its final state only does not open at its end (0.8 s): " + json.dumps(final)[:500])
    check_diverged(drapelab, chromium, scene, work)
    print(f"OK: {len(renders)} pictures, {page.stat().st_size / 1e6:.2f} MB page; "
          f"a final state only opens at t = {opened_at[0]}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
