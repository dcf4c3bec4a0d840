"""The replay folder of a live session (docs/live.md, "Output") in the cases that broke it.

1. A key pressed live on a scene whose hands come from inline `input.events` that go on after
   it (fig2_hold.json: hand events up to 2.5 s): the key joins the events in time order, and
   `drapelab run OUT/scene.json` replays the same events. Appended at the end, it made the
   events' times go backwards and the replay was refused (exit 2).
2. Live hands that never moved and no key: nothing to record, so no recording.jsonl (drapelab's
   reader refuses a file without frames), `live.recording` null in summary.json, and the replay
   scene has no hand input; it replays.
3. summary.json is written last: a folder without it is not finished (docs/outputs.md).
4. `output.event_trace_interval` gives live the event_trace/ of `drapelab run` (it was ignored),
   the same frames as the replay's.
5. Stopped by Ctrl-C, energy.csv and hands.csv end with the stop time's row, as the replay's do.
6. A key answered `ok` just before Ctrl-C is in the events (applied, or listed as ignored after
   the end) of the live run and of its replay alike; it vanished from both.
7. A dummy mesh named relative to the live scene's folder is found by the replay scene, which
   lives in OUT (the relative name was copied as it was).
8. The replay keeps the live run's runaway bound (`runaway_horizon`): a live run beyond the
   stability limit that stopped `ok` on Ctrl-C replays `ok`, and one that diverged diverges at
   the same time for the same reason (the replay's shorter duration shrank the bound, so it
   diverged where the live run had not, or earlier).
Usage: live_replay_check.py DRAPELAB SOURCE_DIR WORK_DIR
"""
import json
import pathlib
import shutil
import signal
import subprocess
import sys
import time
import urllib.request

import numpy

from live_client import LiveRun, check_arguments, free_port, replay_events


def key_between_scene_events(drapelab, source, work):
    out = work / "keys"
    with LiveRun(drapelab, source / "experiments/scenes/fig2_hold.json", out) as run:
        run.wait_for(lambda f: f["t"] > 0.1, "the first frames")
        assert run.post("/key", "r") == (200, "ok\n")
        run.wait_for(lambda f: f["t"] > 1.0 and f["event_count"] >= 1, "the key's event")
        code, stdout, stderr = run.stop()
        assert code == 0, (code, stdout, stderr)
    scene = json.loads((out / "scene.json").read_text())
    times = [e["t"] for e in scene["input"]["events"]]
    assert times == sorted(times) and len(set(times)) == len(times), times
    assert any(e.get("keys") == ["r"] for e in scene["input"]["events"]), scene["input"]["events"]
    events = json.loads((out / "summary.json").read_text())["events"]
    assert events and replay_events(drapelab, out, work / "keys_replay") == events, events
    # stopped by Ctrl-C, the live run writes the stop time's rows, which its replay ends with
    for name in ("energy.csv", "hands.csv"):
        live, replayed = (out / name).read_text(), (work / "keys_replay" / name).read_text()
        assert live == replayed, (name, live.splitlines()[-2:], replayed.splitlines()[-2:])
    print(f"a live key among the scene's events at {times}: replayed {len(events)} events alike")


def live_hands_without_input(drapelab, source, work):
    out = work / "empty"
    with LiveRun(drapelab, source / "experiments/scenes/fig2_hold.json", out, "--live-hands") as run:
        run.wait_for(lambda f: f["t"] > 0.3, "a few frames")
        code, stdout, stderr = run.stop()
        assert code == 0, (code, stdout, stderr)
    summary = json.loads((out / "summary.json").read_text())
    assert summary["live"]["recording"] is None, summary["live"]
    assert not (out / "recording.jsonl").exists()
    scene = json.loads((out / "scene.json").read_text())
    assert "recording" not in scene["input"] and "events" not in scene["input"], scene["input"]
    assert replay_events(drapelab, out, work / "empty_replay") == summary["events"] == []
    print("live hands that never moved: no recording, the replay runs with no events")


def failed_last_write(drapelab, source, work):
    out = work / "late"
    with LiveRun(drapelab, source / "experiments/scenes/fig2_hold.json", out) as run:
        run.wait_for(lambda f: f["t"] > 0.1, "the first frames")
        (out / "recording.jsonl").mkdir()  # stands for a disk that fills at the end
        assert run.post("/key", "r") == (200, "ok\n")
        run.wait_for(lambda f: f["event_count"] >= 1, "the key's event")
        code, stdout, stderr = run.stop()
    assert code == 4 and "recording.jsonl" in stderr, (code, stderr)
    assert not (out / "summary.json").exists(), sorted(p.name for p in out.iterdir())
    print(f"a failed write of recording.jsonl: exit 4, no summary.json ({stderr.strip()})")


def event_trace(drapelab, source, work):
    out, replay = work / "event_trace", work / "event_trace_replay"
    trace = ["--set", "output.event_trace_interval=0.001", "--set", "duration=0.3"]
    subprocess.run([drapelab, "live", source / "experiments/scenes/fig6_map.json", "--port",
                    str(free_port()), "--out", out, *trace], check=True, timeout=60,
                   stdout=subprocess.DEVNULL)
    subprocess.run([drapelab, "run", out / "scene.json", "--out", replay, "-q", *trace],
                   check=True, timeout=60)
    for name in ("t", "x", "v", "fixed", "contact"):
        live = numpy.load(out / "event_trace" / f"{name}.npy")
        assert numpy.array_equal(live, numpy.load(replay / "event_trace" / f"{name}.npy")), name
    print(f"event_trace/ in live: {len(live)} frames, as the replay's")


def relative_mesh(drapelab, source, work):
    folder = work / "scene_folder"
    folder.mkdir()
    shutil.copy(source / "core/dummy/data/dress-form/mh_default_female_body_cm.obj",
                folder / "body.obj")
    scene = json.loads((source / "experiments/scenes/fig6_map.json").read_text())
    scene["dummy"] = {"mesh": "body.obj", "unit": 0.01}
    (folder / "scene.json").write_text(json.dumps(scene))
    out = work / "relative_mesh"
    subprocess.run([drapelab, "live", folder / "scene.json", "--port", str(free_port()), "--out",
                    out, "--set", "duration=0.2"], check=True, timeout=60, stdout=subprocess.DEVNULL)
    replayed = json.loads((out / "scene.json").read_text())["dummy"]["mesh"]
    assert pathlib.Path(replayed) == (folder / "body.obj").resolve(), replayed
    events = json.loads((out / "summary.json").read_text())["events"]
    assert replay_events(drapelab, out, work / "relative_mesh_replay") == events, events
    print(f"a relative dummy.mesh: the replay scene names {replayed}")


def key_before_ctrl_c(drapelab, source, work):
    # The key and Ctrl-C inside one loop turn's sleep (most of the 1/30 s turn), as a person
    # pressing a key and Ctrl-C at once: the key is taken after the last turn.
    for mode in ([], ["--live-hands"]):
        out = work / ("late_key" + "".join(mode))
        port = free_port()
        live = subprocess.Popen([drapelab, "live", source / "experiments/scenes/fig6_map.json",
                                 "--port", str(port), "--out", out, "--set", "duration=60", *mode],
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        live.stdout.readline()  # listening
        time.sleep(0.5)
        request = urllib.request.Request(f"http://127.0.0.1:{port}/key", data=b"r", method="POST")
        assert urllib.request.urlopen(request, timeout=10).read() == b"ok\n"
        live.send_signal(signal.SIGINT)
        assert live.wait(timeout=60) == 0, live.stderr.read()
        events = json.loads((out / "summary.json").read_text())["events"]
        assert any(e.get("key") == "r" for e in events), events
        assert replay_events(drapelab, out, work / f"{out.name}_replay") == events, events
        print(f"a key just before Ctrl-C{''.join(' ' + m for m in mode)}: "
              f"{[e for e in events if e.get('key') == 'r']}")


def runaway_bound(drapelab, source, work):
    scene = source / "experiments/scenes/fig2_hold.json"
    # diverges within 0.02 s of simulated time, long before the duration
    out = work / "runaway"
    live = subprocess.run([drapelab, "live", scene, "--port", str(free_port()), "--out", out,
                           "--set", "integrator.dt=0.005", "--set", "duration=5"],
                          capture_output=True, text=True, timeout=60)
    replay = subprocess.run([drapelab, "run", out / "scene.json", "--out", work / "runaway_replay",
                             "-q"], capture_output=True, text=True, timeout=60)
    assert live.returncode == replay.returncode == 3, (live, replay)
    summaries = [json.loads((d / "summary.json").read_text()) for d in (out, work / "runaway_replay")]
    live_end, replay_end = [(s["status"], s["sim_time"], s["reason"]) for s in summaries]
    assert live_end == replay_end, (live_end, replay_end)
    # beyond the stability limit, saturating below the bound of a 600 s session: stopped after 3 s
    out = work / "saturated"
    with LiveRun(drapelab, scene, out, "--set", "integrator.dt=0.00062", "--set", "duration=600") as run:
        run.wait_for(lambda f: f["t"] > 2.0, "2 s of the unstable run")
        code, stdout, stderr = run.stop()
        assert code == 0, (code, stdout, stderr)
    live_summary = json.loads((out / "summary.json").read_text())
    replay_events(drapelab, out, work / "saturated_replay")
    replayed = json.loads((work / "saturated_replay" / "summary.json").read_text())
    assert replayed["status"] == "ok" and replayed["events"] == live_summary["events"], replayed
    assert replayed["energy_final"] == live_summary["energy_final"], (replayed, live_summary)
    print(f"the runaway bound: diverged live and in the replay at {summaries[0]['sim_time']} s; "
          f"{live_summary['sim_time']:.2f} s beyond the stability limit (energy drift "
          f"{live_summary['energy_drift_max_rel']:.3g}) replays ok")


def main():
    drapelab, source, work = check_arguments(sys.argv)
    key_between_scene_events(drapelab, source, work)
    live_hands_without_input(drapelab, source, work)
    failed_last_write(drapelab, source, work)
    event_trace(drapelab, source, work)
    relative_mesh(drapelab, source, work)
    key_before_ctrl_c(drapelab, source, work)
    runaway_bound(drapelab, source, work)


if __name__ == "__main__":
    main()
