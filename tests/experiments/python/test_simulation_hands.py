"""Hands and keys driven from Python (Simulation(scene, live_hands=True), set_hand, press) give
the events that the same hand track replayed from its recording gives (docs/python.md)."""
import numpy as np

import drapelab
from conftest import scene

# Combination 4's right hand (experiments/scenes/combination4_hold_release_attach.json): it comes
# to the cloth, takes a particle, r frees the right corner at 1.0 s, a attaches at 2.0 s.
TRACK = [(0.0, (0.30, 0.95, 0.40)), (0.6, (0.13, 1.06, 0.23)), (1.0, (0.13, 1.06, 0.25)),
         (1.8, (0.08, 1.10, 0.17)), (2.0, (0.08, 1.10, 0.17))]
KEYS = {30: "r", 60: "a"}  # frame (1/30 s) at which each key is pressed
FRAMES = 66


def hand_at(t):
    times = [p[0] for p in TRACK]
    return tuple(np.interp(t, times, [p[1][k] for p in TRACK]) for k in range(3))


def drive(sim):
    """Plays the track at 30 frames a second as the live page does, stepping one step at a time;
    returns the particle hold_candidate named just before the step that made the hold."""
    candidate = None
    for frame in range(FRAMES):
        t = frame / 30
        sim.set_hand("right", hand_at(t) if frame <= 60 else None)
        if frame in KEYS:
            sim.press(KEYS[frame])
        while sim.time < t + 1 / 30:
            before = sim.hold_candidate("right")
            held = bool(sim.events)
            sim.step()
            if not held and sim.events:
                candidate = before
    return candidate


def test_hold_and_attach_from_python_replay_from_their_recording(tmp_path):
    # The scene's own hands and keys taken out: every key and hand comes from Python.
    base = scene("combination4_hold_release_attach.json", duration=2.4,
                 input={"max_gap": 10, "events": []})
    sim = drapelab.Simulation(base, live_hands=True)
    candidate = drive(sim)
    events = sim.events
    assert [e["type"] for e in events] == ["hold", "release", "attach", "attach_fixed"]
    assert events[0]["particle"] == candidate  # the particle nearest the hand is the one it took
    replay = sim.write_recording(tmp_path / "recording.jsonl")
    frames = (tmp_path / "recording.jsonl").read_text().splitlines()
    assert len(frames) > 60 and '"r"' in "".join(frames) and '"a"' in "".join(frames)
    again = drapelab.Simulation(drapelab.Scene.from_dict(replay))
    again.advance(replay["duration"])
    assert again.events == events
    assert again.time == sim.time
    np.testing.assert_array_equal(again.positions, sim.positions)


def test_a_key_pressed_is_applied_one_step_later():
    # The scene's own keys play as they are; a key pressed is applied one step after the press.
    sim = drapelab.Simulation(scene("fig2_hold.json", duration=1.0))
    sim.advance(0.8)
    assert [e["type"] for e in sim.events] == ["hold"]
    pressed_at = sim.time
    sim.press("r")
    sim.advance(0.9)
    release = sim.events[-1]
    assert release["type"] == "release"
    assert release["t"] == pressed_at + 2e-4
