"""Bad input to the Python API raises the exception it should, naming what was wrong, and ends
no interpreter: each case runs in its own process, which must exit normally (docs/python.md,
"Errors")."""
import os
import subprocess
import sys
import textwrap

import pytest

from conftest import SCENES, child_env

PRELUDE = f"""
import math, numpy as np, drapelab
HOLD = {str(SCENES / "fig2_hold.json")!r}
def short(**o):
    o.setdefault("duration", 0.05)
    return drapelab.Simulation(drapelab.load_scene(HOLD, overrides=o))
"""

# (case, the code that must raise, the exception, a text its message holds)
CASES = [
    ("missing file", "drapelab.load_scene('no/such/scene.json')", "InputError", "no/such/scene.json"),
    ("path of a wrong type", "drapelab.load_scene(42)", "TypeError", ""),
    ("overrides not a dict", "drapelab.load_scene(HOLD, overrides=['duration=1'])", "InputError", "overrides"),
    ("override key not a string", "drapelab.load_scene(HOLD, overrides={1: 2})", "InputError", "overrides"),
    ("NaN override", "drapelab.load_scene(HOLD, overrides={'integrator.dt': math.nan})", "InputError",
     "overrides['integrator.dt']"),
    ("unknown key", "drapelab.load_scene(HOLD, overrides={'cloth.nosuch': 1})", "InputError", "nosuch"),
    ("value out of range", "drapelab.load_scene(HOLD, overrides={'integrator.dt': -1})", "InputError",
     "overrides['integrator.dt']: integrator.dt"),
    ("object as a value", "drapelab.load_scene(HOLD, overrides={'duration': object()})", "InputError",
     "object is not a JSON value"),
    ("scene dict not a dict", "drapelab.Scene.from_dict([1, 2])", "InputError", "Scene.from_dict"),
    ("scene dict without cloth", "drapelab.Scene.from_dict({'duration': 1})", "InputError", "cloth"),
    ("self-nested scene", "d = {}; d['cloth'] = d; drapelab.Scene.from_dict(d)", "InputError", "deeper"),
    ("simulation of a non-scene", "drapelab.Simulation('scene.json')", "TypeError", ""),
    ("advance to NaN", "short().advance(math.nan)", "InputError", "Simulation.advance: t"),
    ("advance to a string", "short().advance('1')", "TypeError", ""),
    ("unknown key pressed", "short().press('x')", "InputError", "Simulation.press: key"),
    ("a hand without live hands", "short().set_hand('right', (0, 1, 0))", "InputError", "live_hands"),
    ("unknown hand", "drapelab.Simulation(drapelab.load_scene(HOLD), live_hands=True).set_hand('middle', (0, 1, 0))",
     "InputError", "Simulation.set_hand: hand"),
    ("NaN hand", "drapelab.Simulation(drapelab.load_scene(HOLD), live_hands=True).set_hand('right', (math.nan, 1, 0))",
     "InputError", "right.x"),
    ("hand of two numbers", "drapelab.Simulation(drapelab.load_scene(HOLD), live_hands=True).set_hand('left', (0, 1))",
     "InputError", "xyz"),
    ("candidate of no hand", "short().hold_candidate('both')", "InputError", "hand"),
    ("positions of a wrong shape", "s = short(); s.positions = np.zeros((3, 3))", "InputError", "(400, 3)"),
    ("positions of text", "s = short(); s.positions = 'abc'", "InputError", "positions"),
    ("NaN positions", "s = short(); p = np.array(s.positions); p[3, 1] = math.nan; s.positions = p",
     "InputError", "finite"),
    ("writing through the view", "s = short(); s.positions[0, 0] = 1.0", "ValueError", "read-only"),
    ("step after close", "s = short(); s.close(); s.step()", "RuntimeError", "closed"),
    ("positions after close", "s = short(); s.close(); s.positions", "RuntimeError", "closed"),
    ("recording without live hands", "short().write_recording('r.jsonl')", "InputError", "live_hands"),
    ("experiment of a missing file", "drapelab.experiment('no/such.json', 'out', jobs=1)", "InputError", "no/such.json"),
    ("experiment jobs", "drapelab.experiment('x.json', 'out', jobs=0)", "InputError", "jobs"),
]


def run(code, tmp_path):
    script = PRELUDE + textwrap.dedent(code)
    return subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                          cwd=tmp_path, env=child_env(), timeout=60)


@pytest.mark.parametrize("case,code,exception,text", CASES, ids=[c[0] for c in CASES])
def test_bad_input_raises_and_ends_nothing(case, code, exception, text, tmp_path):
    probe = f"""
try:
    {code}
except drapelab.InputError as e:
    assert isinstance(e, ValueError)
    print('InputError', e)
except Exception as e:
    print(type(e).__name__, e)
else:
    print('nothing raised')
"""
    done = run(probe, tmp_path)
    assert done.returncode == 0, done.stderr
    assert done.stdout.split(" ", 1)[0] == exception, done.stdout
    assert text in done.stdout, done.stdout


def test_calls_after_a_failure_raise_it_again_with_the_state_readable(tmp_path):
    # Leap-frog at 10 ms is far beyond its stable step on this cloth (0.59 ms): it diverges.
    done = run("""
s = short(duration=5.0, **{'integrator.dt': 0.01})
for attempt in range(2):
    try:
        s.advance(5.0)
    except drapelab.IntegratorFailure as e:
        assert isinstance(e, RuntimeError)
        print(e.flag, e.status, e.time == s.time, s.time < 5.0)
print(s.positions.shape, s.status)
s.close()
s.close() if not s.closed else print('closed')
""", tmp_path)
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines() == ["diverged diverged True True"] * 2 + [
        "(400, 3) diverged", "closed"]


@pytest.mark.parametrize("integrator,flag", [
    # One Newton iteration cannot solve a DIRK stage at half a second: ARKODE's flag.
    ({"name": "arkode-dirk", "dt": 0.5, "max_newton_iters": 1}, "ARK_CONV_FAILURE"),
    ({"name": "arkode-erk", "adaptive": True, "dt": 1e-4, "max_steps": 5}, "max_steps")])
def test_a_solver_failure_names_its_flag(integrator, flag, tmp_path):
    done = run(f"""
s = short(integrator={integrator!r}, duration=1.0)
try:
    s.advance(1.0)
except drapelab.IntegratorFailure as e:
    print(e.flag, e.status)
""", tmp_path)
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == [flag, "failed"]


def test_a_view_outlives_its_closed_simulation(tmp_path):
    done = run("""
s = short()
s.advance(0.01)
p = s.positions
kept = p.copy()
s.close()
del s
import gc; gc.collect()
print(bool((p == kept).all()), p.shape)
""", tmp_path)
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == ["True", "(400,", "3)"]
