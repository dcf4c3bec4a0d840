#!/usr/bin/env python3
"""Whether `drapelab live` keeps up with the wall clock (docs/performance/threads.md, "Real time"):
the dress-form drape of real_time_table.py (experiments/scenes/drape_dress_form.json with the
smooth model, the cloth 0.4 m square with its total mass at every n, the method at 1/30 s with
its default keys), served by `drapelab live`; the script reads the page's event stream for
SECONDS and prints the last frame's simulated time `t`, wall time `wall` (since the start, the
scene's set-up included), real-time factor `rtf = t / wall` and `behind` (more than 0.1 s behind
the wall clock: docs/live.md, "Protocol"), then stops the run with SIGINT.

    /usr/bin/python3 experiments/benchmarks/live_real_time.py implicit-euler 96 [--seconds 15]

Run it on an idle machine: the wall clock is the measurement."""
import argparse
import json
import os
import signal
import subprocess
import sys
import tempfile
import time
import urllib.request

from real_time_table import FRAME, ROOT, SCENE, SIDE, TOTAL_MASS


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("method")
    parser.add_argument("n", type=int)
    parser.add_argument("--seconds", type=float, default=15.0)
    parser.add_argument("--port", type=int, default=8731)
    parser.add_argument("--drapelab", default=os.path.join(ROOT, "build", "bin", "drapelab"))
    args = parser.parse_args()
    n = args.n
    sets = {"cloth.rows": n, "cloth.cols": n, "cloth.spacing": SIDE / (n - 1),
            "cloth.particle_mass": TOTAL_MASS / (n * n), "pins": f"[[0,0],[0,{n - 1}]]",
            "collision.model": "smooth", "duration": 600, "integrator.name": args.method,
            "integrator.dt": FRAME}
    with tempfile.TemporaryDirectory() as out:
        command = [args.drapelab, "live", SCENE, "--port", str(args.port), "--out", out, "--overwrite"]
        for key, value in sets.items():
            command += ["--set", f"{key}={value}"]
        live = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        try:
            time.sleep(1.5)
            last, frames, end = None, 0, time.monotonic() + args.seconds
            with urllib.request.urlopen(f"http://127.0.0.1:{args.port}/events", timeout=30) as stream:
                for line in stream:
                    if line.startswith(b"data: "):
                        last = json.loads(line[6:])
                        frames += 1
                    if time.monotonic() > end:
                        break
        finally:
            live.send_signal(signal.SIGINT)
            live.wait(timeout=30)
    if last is None:
        print("no frame read", file=sys.stderr)
        return 1
    print(f"{args.method} {n} x {n}: frames {frames} t {last['t']:.3f} wall {last['wall']:.3f} "
          f"rtf {last['rtf']:.3f} behind {last['behind']}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
