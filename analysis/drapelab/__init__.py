"""drapelab from Python: scenes, simulations stepped from a program, experiments (docs/python.md).

    import drapelab
    scene = drapelab.load_scene("experiments/scenes/fig2_hold.json", overrides={"duration": 1.0})
    sim = drapelab.Simulation(scene)
    sim.advance(0.5)            # to t = 0.5 s, the events on the way applied
    sim.positions               # (N, 3) read-only view of the state [m]
    sim.run("out/fig2")         # on a new Simulation: drapelab run's folder, the same bytes

The simulation itself is the compiled module _drapelab, built with the C++ (build/python/);
drapelab.analysis is the analysis package (drapeanalysis) under its new name.
"""
import importlib
import os
import pathlib
import subprocess
import sys


def _compiled_module():
    # install_dependencies.sh's .pth names build/python; a checkout whose .pth predates that,
    # or none (PYTHONPATH=analysis), finds the build beside the package.
    try:
        return importlib.import_module("_drapelab")
    except ModuleNotFoundError as missing:
        build = pathlib.Path(__file__).resolve().parents[2] / "build" / "python"
        if not build.is_dir():
            raise ImportError(
                f"drapelab's compiled module is not built: run `cmake --preset release && "
                f"cmake --build --preset release` in {build.parents[1]}") from missing
        sys.path.append(str(build))
        return importlib.import_module("_drapelab")


_core = _compiled_module()
InputError = _core.InputError
IntegratorFailure = _core.IntegratorFailure
Scene = _core.Scene
Simulation = _core.Simulation
load_scene = _core.load_scene
integrators = _core.integrators
tables = _core.tables
fabrics = _core.fabrics
version = _core.version


def experiment(definition, out, jobs=2, overwrite=False):
    """Runs an experiment file into `out` as `drapelab experiment` does (each run in its own
    process, `jobs` at a time; docs/experiments.md) and returns its results table (a pandas
    DataFrame, one row per run). Bad input raises InputError; Ctrl-C stops the experiment's runs."""
    if not isinstance(jobs, int) or isinstance(jobs, bool) or not 1 <= jobs <= 1024:
        error = InputError(f"experiment: jobs: expected an integer in [1, 1024], got {jobs!r}")
        error.file, error.field, error.message = "experiment", "jobs", str(error)
        raise error
    command = [_core.DRAPELAB_EXECUTABLE, "experiment", os.fspath(definition), "--out",
               os.fspath(out), "--jobs", str(jobs), "--no-progress"]
    if overwrite:
        command.append("--overwrite")
    done = subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                          check=False)
    message = done.stderr.strip().splitlines()
    if done.returncode == 2:
        error = InputError(message[-1].removeprefix("drapelab: error: ") if message else
                           f"experiment {definition}: bad input")
        error.file, error.field, error.message = os.fspath(definition), "", str(error)
        raise error
    if done.returncode != 0:
        raise RuntimeError(f"drapelab experiment {definition} ended with status "
                           f"{done.returncode}: " + "\n".join(message[-5:]))
    from drapeanalysis import results_table
    return results_table(os.fspath(out))


def __getattr__(name):
    # drapelab.analysis imported on first use: matplotlib and pandas load only when asked for.
    if name == "analysis":
        return importlib.import_module(".analysis", __name__)
    raise AttributeError(f"module 'drapelab' has no attribute {name!r}")


__all__ = ["InputError", "IntegratorFailure", "Scene", "Simulation", "load_scene", "integrators",
           "tables", "fabrics", "version", "experiment", "analysis"]
