"""Live hands end to end (docs/live.md, "Live hands", "Sensor bridge").

`drapelab live fig2_hold.json --live-hands --sensor-port Q`: POST /hand refuses a body that is
not JSON (NaN), a coordinate out of range, a missing one and an unknown hand with 400 and a
message; a valid one moves the right hand to the posted point; moved onto particle (14, 10) the
hand holds it; a sensor bridge client writing JSON Lines (a header, three malformed lines, frames)
moves the hand and the held particle with it; `r` releases; the hand taken away, the run goes
on. After SIGINT: the summary has the
hold and the release, the malformed lines were reported and ignored, recording.jsonl holds the
hand frames, and `drapelab run OUT/scene.json` replays the same events. Without --live-hands
a scene with recorded hands answers POST /hand with 409.
Usage: live_hands_check.py DRAPELAB SOURCE_DIR WORK_DIR
"""
import base64
import json
import pathlib
import socket
import struct
import sys
import time

from live_client import LiveRun, check_arguments, free_port, replay_events

HELD = 14 * 20 + 10  # particle (14, 10) of the 20 x 20 cloth: x = 0.01, y = 1.02, z = 0.22


def right_hand(frame):
    return next(h for h in frame["hands"] if h["hand"] == "right")


def near(a, b, tolerance):
    return all(abs(x - y) <= tolerance for x, y in zip(a, b))


def particle(frame, i):
    raw = base64.b64decode(frame["positions"])
    return struct.unpack_from("<3f", raw, 12 * i)


def check_validation(run):
    for body, expect in [('{"x": NaN, "y": 1, "z": 0}', "not valid JSON"),
                         ('{"x": 0, "y": 1e9, "z": 0}',
                          "POST /hand: right.y: 1000000000 is not a scene coordinate within +-10 m"),
                         ('{"x": 0, "y": 1}', "POST /hand: z: required field is missing"),
                         ('{"hand": "middle", "x": 0, "y": 1, "z": 0}', "POST /hand: hand: expected"),
                         ('{"x": 0, "y": 1, "z": 0, "speed": 2}', "POST /hand: speed: unknown key")]:
        status, text = run.post("/hand", body)
        assert status == 400 and expect in text, (body, status, text)


def main():
    drapelab, source, work = check_arguments(sys.argv)
    scene = source / "experiments/scenes/fig2_hold.json"
    out = work / "live"
    sensor_port = free_port()
    with LiveRun(drapelab, scene, out, "--live-hands", "--sensor-port", sensor_port,
                      "--set", "duration=60") as run:
        check_validation(run)

        # the pointer: POST /hand in the scene frame
        start = (0.01, 0.95, 0.40)
        assert run.post("/hand", json.dumps(dict(zip("xyz", start)))) == (200, "ok\n")
        frame = run.wait_for(lambda f: right_hand(f)["available"] and
                             near(right_hand(f)["position"], start, 1e-12), "the posted hand")
        assert right_hand(frame)["held"] == -1
        assert run.post("/hand", '{"x": 0.01, "y": 1.02, "z": 0.23}') == (200, "ok\n")
        frame = run.wait_for(lambda f: right_hand(f)["held"] == HELD, "the hold of (14, 10)")
        print(f"pointer: holds particle {HELD} at t = {frame['t']:.3f} s")

        # the sensor bridge: JSON Lines as in a recording; malformed lines are reported, ignored
        lift = (0.06, 1.16, 0.36)
        with socket.create_connection(("127.0.0.1", sensor_port), timeout=10) as bridge:
            lines = ['{"format": "drapelab-recording", "version": 1}',
                     '{"t": 0.0, "right": [0.0, "up", 0.0]}',
                     'not json',
                     '{"t": 0.05, "right": [0.0, 50.0, 0.0]}',
                     *[json.dumps({"t": 0.1 * k, "right": list(lift)}) for k in range(1, 4)]]
            # No newline after the last line (a file piped in that does not end in one): it is
            # still a line, read when the connection closes (it was dropped without a word).
            bridge.sendall("\n".join(lines).encode())
            frame = run.wait_for(lambda f: near(right_hand(f)["position"], lift, 1e-12) and
                                 f["t"] > frame["t"] + 0.2, "the sensor's hand")
        assert right_hand(frame)["held"] == HELD
        # a held particle is fixed to the hand (docs/manipulations.md): float32 of the same point
        assert near(particle(frame, HELD), lift, 1e-6), (particle(frame, HELD), lift)
        print(f"sensor: hand and particle {HELD} at {lift} at t = {frame['t']:.3f} s")

        # A client that connects and sends nothing holds the next one back: the terminal says so.
        with socket.create_connection(("127.0.0.1", sensor_port), timeout=10), \
                socket.create_connection(("127.0.0.1", sensor_port), timeout=10):
            time.sleep(0.5)

        assert run.post("/key", "r") == (200, "ok\n")
        run.wait_for(lambda f: any(e["type"] == "release" for e in f["events"]), "the release")
        # the hand taken away: the run goes on without it (it must not stop for good at the
        # hand's sample before the last)
        assert run.post("/hand", '{"hand": "right", "tracked": false}') == (200, "ok\n")
        gone = run.wait_for(lambda f: not right_hand(f)["available"], "the hand taken away")
        frame = run.wait_for(lambda f: f["t"] > gone["t"] + 1.0, "the run going on without a hand")
        print(f"hand taken away at t = {gone['t']:.3f} s; the run at t = {frame['t']:.3f} s")
        code, stdout, stderr = run.stop()
        assert code == 0, (code, stdout, stderr)
        assert "sensor bridge: 3 frames, 3 malformed lines ignored" in stdout, stdout
        assert "connection 1: line 2.right: expected an array of numbers" in stderr, stderr
        assert "connection 1: line 3: not valid JSON" in stderr, stderr
        assert "connection 1: line 4: right.y: 50 is not a scene coordinate" in stderr, stderr
        assert "connection 2: another sensor connection waits until this one closes" in stderr, stderr

        summary = json.loads((out / "summary.json").read_text())
        assert summary["status"] == "stopped", summary["status"]
        assert summary["live"]["hands"] == "live", summary["live"]
        events = summary["events"]
        types = [e["type"] for e in events]
        assert "hold" in types and "release" in types, events
        replay_scene = json.loads((out / "scene.json").read_text())
        assert pathlib.Path(replay_scene["input"]["recording"]) == (out / "recording.jsonl").resolve()
        recording = (out / "recording.jsonl").read_text().splitlines()
        hands = [json.loads(l) for l in recording[1:] if '"right":[' in l.replace(" ", "")]
        assert len(hands) > 10 and any(near(h["right"], lift, 0) for h in hands), recording[:5]
        replayed = replay_events(drapelab, out, work / "replay")
        assert replayed == events, (replayed, events)
        print(f"live hands: events {events} replayed alike from {len(recording) - 1} recorded frames")

        # recorded hands without --live-hands: the pointer may not take over
        fixed = LiveRun(drapelab, scene, work / "recorded", "--set", "duration=60")
        status, text = fixed.post("/hand", '{"x": 0, "y": 1, "z": 0}')
        assert status == 409 and "--live-hands" in text, (status, text)
        assert fixed.stop()[0] == 0


if __name__ == "__main__":
    main()
