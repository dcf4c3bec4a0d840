#!/usr/bin/env python3
"""The largest n x n cloth each method steps in real time (docs/performance/threads.md, "Real
time"): the dress-form drape of experiments/scenes/drape_dress_form.json with the smooth contact
model, the cloth kept 0.4 m square with its mass, so that only the resolution changes (a
membrane's spring constant does not depend on the spacing; the particle mass is the total over
n^2). Each method at 1/30 s with its default keys; leap-frog at 4e-3/n s, its stable step scaling
with the spacing (0.2 ms at the scene's 21 columns). Prints, per method and n, the wall seconds of
stepping per simulated second (`wall_seconds / sim_time` of summary.json; real time is <= 1) and
stops a method at the first n it runs slower than a quarter of real time.

    /usr/bin/python3 experiments/benchmarks/real_time_table.py [--threads N] [--sizes 32,64,128]

Run it on an idle machine: the wall time is the measurement."""
import argparse
import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENE = os.path.join(ROOT, "experiments", "scenes", "drape_dress_form.json")
SIDE = 0.4                   # m: the cloth's side at every n
TOTAL_MASS = 6e-5 * 25 * 21  # kg: the scene's cloth
FRAME = 1.0 / 30.0
METHODS = ["leapfrog", "implicit-euler", "projective-dynamics", "bdf2", "xpbd", "vbd"]


def cost(drapelab, method, n, threads, duration, out):
    dt = 4e-3 / n if method == "leapfrog" else FRAME
    sets = {"cloth.rows": n, "cloth.cols": n, "cloth.spacing": SIDE / (n - 1),
            "cloth.particle_mass": TOTAL_MASS / (n * n), "pins": f"[[0,0],[0,{n - 1}]]",
            "collision.model": "smooth", "duration": duration,
            "integrator.name": method, "integrator.dt": dt}
    args = [drapelab, "run", SCENE, "--out", out, "--overwrite", "--quiet", "--threads", str(threads)]
    for key, value in sets.items():
        args += ["--set", f"{key}={value}"]
    subprocess.run(args, check=True)
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    if summary["status"] != "ok":
        return None, summary["status"]
    return summary["wall_seconds"] / summary["sim_time"], "ok"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--drapelab", default=os.path.join(ROOT, "build", "bin", "drapelab"))
    parser.add_argument("--threads", type=int, default=os.cpu_count())
    parser.add_argument("--sizes", default="32,48,64,96,128")
    parser.add_argument("--duration", type=float, default=1.0)
    args = parser.parse_args()
    sizes = [int(s) for s in args.sizes.split(",")]
    print(f"threads {args.threads}; wall s of stepping per simulated s (real time <= 1)")
    print("| method | " + " | ".join(f"{n} x {n}" for n in sizes) + " | largest in real time |")
    print("|---|" + "---|" * (len(sizes) + 1))
    with tempfile.TemporaryDirectory() as tmp:
        for method in METHODS:
            cells, largest = [], "none"
            for n in sizes:
                value, status = cost(args.drapelab, method, n, args.threads, args.duration,
                                     os.path.join(tmp, f"{method}-{n}"))
                if value is None:
                    cells.append(status)
                    break
                cells.append(f"{value:.3g}")
                if value <= 1.0:
                    largest = f"{n} x {n}"
                if value > 4.0:
                    break
            cells += ["-"] * (len(sizes) - len(cells))
            print(f"| {method} | " + " | ".join(cells) + f" | {largest} |", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
