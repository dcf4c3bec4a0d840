"""The live loop's pace against the wall clock (docs/live.md, "Real-time factor").

A slow step rate (30 x 30, adaptive DIRK at the cloth's stiffness) still publishes frames and
stops on Ctrl-C within a turn or so: it stepped through a whole 1/30 s of simulated time before
looking at either, and Ctrl-C waited for minutes. A run that can keep up and was held up (stopped
for 1.5 s, as a stall at the start or a busy machine does) closes the gap to the wall clock and
the "behind" badge goes: a loop that advanced at most 1/30 s a turn stayed behind by the stall
for good while the real-time factor read 1.00.
Both are wall-clock measurements, so ctest runs this check alone (RUN_SERIAL): beside other tests
on two cores the sanitizer build did not catch up within the 20 s the check then waited (the
gap closes at its spare speed, 0.2 to 0.35 s/s when it runs alone).
Usage: live_pace_check.py DRAPELAB SOURCE_DIR WORK_DIR
"""
import signal
import sys
import time

from live_client import LiveRun, check_arguments


def slow_run_publishes_and_stops(drapelab, scene, work):
    slow = LiveRun(drapelab, scene, work / "slow", "--set", "duration=60", "--set",
                   "integrator.name=arkode-dirk", "--set", "integrator.adaptive=true", "--set",
                   "integrator.dt=1e-3", "--set", "cloth.rows=30", "--set", "cloth.cols=30")
    with slow:
        slow.wait_for(lambda f: True, "a first frame")
        time.sleep(2)
        published = len(slow.frames)
        asked = time.monotonic()
        code, _, _ = slow.stop()
        took = time.monotonic() - asked
    assert code == 0 and took < 10 and published >= 10, (code, took, published)
    print(f"slow run: {published} frames in 2 s, stopped {took:.1f} s after Ctrl-C")


def gap(frame):
    """How far the simulation is behind the wall clock, s."""
    return frame["wall"] - frame["t"]


def stalled_run_catches_up(drapelab, scene, work):
    stalled = LiveRun(drapelab, scene, work / "stalled", "--set", "duration=60")
    with stalled:
        before = stalled.wait_for(lambda f: f["wall"] > 1.0, "1 s of wall clock")
        if before["behind"]:  # a build too slow to keep up at all has nothing to catch up to
            print(f"stalled run: not checked, this build cannot keep up (rtf {before['rtf']:.2f})")
        else:
            stalled.proc.send_signal(signal.SIGSTOP)
            time.sleep(1.5)
            stalled.proc.send_signal(signal.SIGCONT)
            behind = stalled.wait_for(lambda f: f["behind"], "the stall to show")
            # The gap closes at the run's spare speed (its real-time factor while catching up,
            # less 1; 0.2 to 0.35 s/s for the sanitizer build alone here): measured over 3 s,
            # it must be above 0.05 s/s (a loop that advanced at most 1/30 s a turn had 0), and
            # the gap must then close within twice the time that speed needs
            later = stalled.wait_for(lambda f: f["wall"] > behind["wall"] + 3.0, "3 s more")
            spare = (gap(behind) - gap(later)) / (later["wall"] - behind["wall"])
            assert not later["behind"] or spare > 0.05, \
                f"the gap stays: {gap(behind):.2f} s, then {gap(later):.2f} s 3 s later"
            needs = gap(later) / spare if later["behind"] else 0.0
            caught_up = stalled.wait_for(lambda f: not f["behind"] and f["wall"] >= later["wall"],
                                         "catching up", timeout=2.0 * needs + 5.0)
            print(f"stalled run: {gap(behind):.2f} s behind at {behind['wall']:.2f} s, "
                  f"{gap(later):.2f} s at {later['wall']:.2f} s, "
                  f"caught up by {caught_up['wall']:.2f} s")
        code, _, _ = stalled.stop()
    assert code == 0, code


def main():
    drapelab, source, work = check_arguments(sys.argv)
    scene = source / "experiments/scenes/fig6_map.json"
    slow_run_publishes_and_stops(drapelab, scene, work)
    stalled_run_catches_up(drapelab, scene, work)


if __name__ == "__main__":
    main()
