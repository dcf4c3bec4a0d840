"""`drapelab live` in a real browser (docs/live.md, "Checks").

Starts `drapelab live fig6_map.json` on a free port, opens the page in headless chromium through
Selenium and chromedriver, waits for streamed frames, checks that the browser logged no error
and that the WebGL canvas is not blank, presses `m` in the page as a user would, sees the map
event arrive, stops the run with SIGINT and checks that the summary has the event at a time
and that `drapelab run OUT/scene.json` replays the same events. Then, with fig2_hold.json and
--live-hands, presses `h` and moves the pointer over the view: the right hand appears where
the pointer put it. With a step 100 times smaller the page says it cannot keep up; after Ctrl-C the page says
"run ended at t = ... s (stopped)". With DRAPE_LIVE_SCREENSHOT=FILE.png it then holds and lifts the cloth through
POST /hand and saves the page seen from 3/4 (docs/images/live.png).
Usage: live_browser_check.py DRAPELAB SOURCE_DIR WORK_DIR   (exit 77: no chromium, driver or
selenium, skipped)
"""
import json
import os
import shutil
import sys
import time

from live_client import LiveRun, check_arguments, replay_events

SCREENSHOT = os.environ.get("DRAPE_LIVE_SCREENSHOT")
CHROMIUM_FLAGS = ["--headless=new", "--no-sandbox", "--use-angle=swiftshader",
                  "--enable-unsafe-swiftshader", "--hide-scrollbars", "--window-size=1000,760",
                  "--host-resolver-rules=MAP * ~NOTFOUND, EXCLUDE 127.0.0.1"]


def browser():
    """A headless chromium under chromedriver, or exit 77 when one of them is missing."""
    chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    driver = shutil.which("chromedriver")
    try:
        from selenium import webdriver
        from selenium.webdriver.chrome.service import Service
    except ImportError:
        chromium = None
    if not chromium or not driver:
        print("SKIP: needs chromium, chromedriver and selenium "
              "(apt install chromium chromium-driver python3-selenium)")
        sys.exit(77)
    options = webdriver.ChromeOptions()
    options.binary_location = chromium
    for flag in CHROMIUM_FLAGS:
        options.add_argument(flag)
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    chrome = webdriver.Chrome(service=Service(driver), options=options)
    chrome.set_script_timeout(120)  # software WebGL on a loaded machine reads pixels slowly
    return chrome


def wait(driver, script, what, timeout=60.0):
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        value = driver.execute_script(script)
        if value:
            return value
        time.sleep(0.05)
    raise AssertionError(f"timed out waiting for {what}")


def check_page(driver, run):
    """Open the page, wait for frames; no error logged, a picture in the canvas."""
    # #test: no antialiasing, faster in software WebGL; the screenshot keeps it
    driver.get(run.url + ("/" if SCREENSHOT else "/#test"))
    wait(driver, "return window.drape && drape.live && drape.live.frames >= 5", "5 frames")
    pixels = driver.execute_script("return drape.live.nonbackground_pixels()")
    share = pixels["nonbackground"] / pixels["pixels"]
    assert share > 0.02, f"canvas nearly blank: {pixels}"
    errors = [e for e in driver.get_log("browser") if e["level"] == "SEVERE"]
    assert not errors, errors
    return share


def key_check(driver, drapelab, source, work):
    from selenium.webdriver.common.action_chains import ActionChains
    out = work / "map"
    with LiveRun(drapelab, source / "experiments/scenes/fig6_map.json", out, "--set", "duration=60") as run:
        # 40 maps before the page opens: its frames carry the newest 32 events, so it fetches
        # the rest from /event-log and shows the same list as the run
        for _ in range(40):
            run.post("/key", "m")
        run.wait_for(lambda f: f["event_count"] >= 41, "40 map events")
        share = check_page(driver, run)
        wait(driver, "return drape.live.events.length >= 41", "the page's list of 41 events")
        shown = driver.execute_script("return document.getElementById('event-list').children.length")
        assert shown == 6, shown
        pressed_at = driver.execute_script("return drape.live.last.t")  # the scene maps at 0.01 s
        ActionChains(driver).send_keys("m").perform()
        event = wait(driver, "var f = drape.live.last; return f.events.filter(function (e) "
                     f"{{ return e.key === 'm' && e.t > {pressed_at}; }})[0]", "the map event in the page")
        assert event["type"] == "map", event
        errors = [e for e in driver.get_log("browser") if e["level"] == "SEVERE"]
        assert not errors, errors
        page_events = driver.execute_script("return drape.live.events")
        code, stdout, stderr = run.stop()
        assert code == 0, (code, stdout, stderr)
        summary = json.loads((out / "summary.json").read_text())
        assert summary["status"] == "stopped", summary["status"]
        events = summary["events"]
        assert event in events, (event, events)  # at the time the page saw it
        assert page_events == events[:len(page_events)], "the page's events are the run's"
        assert replay_events(drapelab, out, work / "map_replay") == events
        print(f"key: {share:.1%} of the canvas drawn; `m` pressed in the page -> map at "
              f"t = {event['t']:.4f} s, replayed alike")


def pointer_check(driver, drapelab, source, work):
    from selenium.webdriver.common.action_chains import ActionChains
    from selenium.webdriver.common.by import By
    with LiveRun(drapelab, source / "experiments/scenes/fig2_hold.json", work / "pointer",
                      "--live-hands", "--set", "duration=60") as run:
        check_page(driver, run)
        ActionChains(driver).send_keys("h").perform()
        canvas = driver.find_element(By.ID, "gl")
        ActionChains(driver).move_to_element_with_offset(canvas, 20, 10).perform()
        # the last position the page posted, once no request is under way
        sent = wait(driver, "var l = drape.live, p = l.hand_point; "
                    "return p && !l.sending && !l.pending && [p.x, p.y, p.z]", "a pointer hand")
        hand = run.wait_for(lambda f: any(h["hand"] == "right" and h["available"] and
                                          all(abs(a - b) < 1e-9 for a, b in zip(h["position"], sent))
                                          for h in f["hands"]), "the pointer's hand in the frames")
        print(f"pointer: hand at {sent} (t = {hand['t']:.3f} s)")
        if SCREENSHOT:  # the hand takes particle (14, 10) and lifts it, seen from 3/4
            ActionChains(driver).send_keys("h").perform()
            run.post("/key", "r")  # whatever the pointer took
            for point in ((0.01, 0.95, 0.40), (0.01, 1.02, 0.23)):
                run.post("/hand", json.dumps(dict(zip("xyz", point))))
                time.sleep(0.5)
            run.wait_for(lambda f: any(h["held"] == 290 for h in f["hands"]), "the hold")
            run.post("/hand", '{"x": 0.06, "y": 1.12, "z": 0.36}')
            time.sleep(1.5)
            driver.find_element(By.CSS_SELECTOR, '[data-camera="three_quarter"]').click()
            time.sleep(0.5)
            driver.save_screenshot(SCREENSHOT)
        assert run.stop()[0] == 0


def behind_check(driver, drapelab, source, work):
    """A step 100 times smaller than fig2_hold's cannot keep up: the page says so."""
    with LiveRun(drapelab, source / "experiments/scenes/fig2_hold.json", work / "behind",
                 "--set", "integrator.dt=2e-6") as run:
        driver.get(run.url + "/#test")
        text = wait(driver, "var b = document.getElementById('behind'); "
                    "return !b.hidden && b.textContent", "the page's 'cannot keep up'")
        rtf = driver.execute_script("return document.getElementById('rtf').textContent")
        frame = run.latest()
        assert text.startswith("cannot keep up: ") and frame["behind"] and frame["rtf"] < 0.5, \
            (text, frame["rtf"])
        assert run.stop()[0] == 0
        print(f"behind: '{text}', '{rtf}'")


def end_check(driver, drapelab, source, work):
    """Ctrl-C ends the session: the page says when and how (at summary.json's sim_time,
    "stopped"), and its markers are sized from the scene's cloth.spacing (0.02 m: radius
    0.35 x 0.02 = 7 mm; docs/live.md, The page)."""
    with LiveRun(drapelab, source / "experiments/scenes/fig6_map.json", work / "end",
                 "--set", "duration=600") as run:
        driver.get(run.url + "/#test")
        wait(driver, "return window.drape && drape.live && drape.live.frames >= 5", "5 frames")
        radius = driver.execute_script("return drape.live.cloth.marker_radius")
        assert abs(radius - 0.007) < 1e-12, radius
        assert run.stop()[0] == 0
        sim_time = json.loads((work / "end" / "summary.json").read_text())["sim_time"]
        text = wait(driver, "var e = document.getElementById('ended'); "
                    "return !e.hidden && e.textContent", "the page's 'run ended'")
        assert text == f"run ended at t = {sim_time:.3f} s (stopped)", (text, sim_time)
        rtf = driver.execute_script("return document.getElementById('rtf').textContent")
        assert not rtf.startswith("connection lost"), rtf
        print(f"end: '{text}', marker radius {radius} m")


def main():
    drapelab, source, work = check_arguments(sys.argv)
    driver = browser()
    try:
        key_check(driver, drapelab, source, work)
        pointer_check(driver, drapelab, source, work)
        behind_check(driver, drapelab, source, work)
        end_check(driver, drapelab, source, work)
    finally:
        driver.quit()


if __name__ == "__main__":
    main()
