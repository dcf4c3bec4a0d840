"""Paths the Python API's tests share: this tree's scenes and the drapelab program of the build
whose module they import (ctest sets DRAPE_SOURCE_DIR and PYTHONPATH, tests/CMakeLists.txt)."""
import os
import pathlib

import pytest

import drapelab

SOURCE = pathlib.Path(os.environ.get("DRAPE_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[3]))
SCENES = SOURCE / "experiments" / "scenes"


@pytest.fixture
def drapelab_exe():
    return drapelab._core.DRAPELAB_EXECUTABLE


def scene(name, **overrides):
    """A shipped scene with `overrides` ({"key.path": value})."""
    return drapelab.load_scene(SCENES / name, overrides=overrides)


def child_env():
    """The environment of a child Python that imports the drapelab this one imported."""
    paths = [str(pathlib.Path(drapelab.__file__).resolve().parents[1]),
             str(pathlib.Path(drapelab._core.__file__).resolve().parent)]
    return dict(os.environ, PYTHONPATH=os.pathsep.join(paths))
