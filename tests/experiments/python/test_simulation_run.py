"""Simulation.run writes drapelab run's folder; advance in pieces steps as one advance does; the
state arrays are read-only views of the state (docs/python.md)."""
import json
import os
import subprocess

import numpy as np
import pytest

import drapelab
from conftest import SCENES, scene

HOLD = "fig2_hold.json"  # the hand takes a particle at about 0.6 s


def test_run_writes_the_bytes_drapelab_run_writes(tmp_path, drapelab_exe):
    subprocess.run([drapelab_exe, "run", str(SCENES / HOLD), "--out", str(tmp_path / "cli"),
                    "--quiet", "--set", "duration=0.8"], check=True)
    summary = drapelab.Simulation(scene(HOLD, duration=0.8)).run(tmp_path / "py")
    assert summary["status"] == "ok"
    assert [e["type"] for e in summary["events"]] == ["hold"]
    assert sorted(os.listdir(tmp_path / "cli")) == sorted(os.listdir(tmp_path / "py"))
    for name in ("state.csv", "energy.csv", "hands.csv"):
        assert (tmp_path / "cli" / name).read_bytes() == (tmp_path / "py" / name).read_bytes(), name


def test_run_refuses_a_simulation_that_has_stepped(tmp_path):
    sim = drapelab.Simulation(scene(HOLD, duration=0.1))
    sim.step()
    with pytest.raises(drapelab.InputError, match="Simulation.run"):
        sim.run(tmp_path / "out")
    assert not (tmp_path / "out").exists()


def test_advance_in_pieces_steps_as_one_advance():
    one = drapelab.Simulation(scene(HOLD, duration=0.8))
    assert one.advance(0.8) is False  # the end
    many = drapelab.Simulation(scene(HOLD, duration=0.8))
    for k in range(1, 161):
        many.advance(k * 0.005)
    assert many.time == one.time == pytest.approx(0.8)
    np.testing.assert_array_equal(many.positions, one.positions)
    np.testing.assert_array_equal(many.velocities, one.velocities)
    assert many.events == one.events and len(one.events) == 1
    assert many.counters == one.counters


def test_step_is_one_step_of_the_scene_dt():
    sim = drapelab.Simulation(scene(HOLD, duration=0.1))
    for k in range(1, 4):
        assert sim.step() is True
        assert sim.counters["steps"] == k
        assert sim.time == pytest.approx(k * 2e-4, rel=1e-12)


def test_positions_view_the_state_without_a_copy():
    sim = drapelab.Simulation(scene(HOLD, duration=0.1))
    positions, velocities = sim.positions, sim.velocities
    assert positions.shape == velocities.shape == (400, 3)
    before = positions.copy()
    sim.step()
    # The same memory, updated by the step: the view held from before sees the new state.
    assert np.shares_memory(positions, sim.positions)
    assert np.shares_memory(velocities, sim.velocities)
    assert not np.array_equal(positions, before)
    np.testing.assert_array_equal(positions, sim.positions)
    assert not positions.flags.writeable
    with pytest.raises(ValueError):
        positions[0, 0] = 1.0
    with pytest.raises(ValueError):
        velocities += 1.0


def test_each_integrator_steps_in_the_viewed_state():
    for declaration in drapelab.integrators():
        sim = drapelab.Simulation(scene(HOLD, duration=0.01, integrator={
            "name": declaration["name"], "dt": 1e-3}))
        positions = sim.positions
        before = positions.copy()
        sim.step()
        assert np.shares_memory(positions, sim.positions), declaration["name"]
        assert not np.array_equal(positions, before), declaration["name"]


def test_setting_positions_copies_and_projects_the_pins():
    sim = drapelab.Simulation(scene(HOLD, duration=0.1))
    view = sim.positions
    fixed = sim.fixed
    assert fixed.dtype == bool and fixed.sum() == 2  # the two pinned corners
    pins = view[fixed].copy()
    lifted = view + np.array([0.0, 0.01, 0.0])
    sim.positions = lifted
    assert np.shares_memory(view, sim.positions)
    np.testing.assert_array_equal(view[fixed], pins)  # projected back onto the pins
    np.testing.assert_array_equal(view[~fixed], lifted[~fixed])
    lifted[0, 0] = 5.0  # a copy was taken
    assert view[0, 0] != 5.0
    sim.velocities = np.ones((400, 3))
    np.testing.assert_array_equal(sim.velocities[~fixed], 1.0)
    np.testing.assert_array_equal(sim.velocities[fixed], 0.0)


def test_energy_is_the_sum_of_its_terms_and_counts_the_fall():
    sim = drapelab.Simulation(scene(HOLD, duration=0.1))
    e0 = sim.energy()
    assert e0["kinetic"] == 0.0
    assert e0["total"] == pytest.approx(e0["kinetic"] + e0["spring"] + e0["gravity"] + e0["collision"])
    sim.advance(0.05)
    e1 = sim.energy()
    mass = 6e-5
    kinetic = 0.5 * mass * np.sum(np.asarray(sim.velocities) ** 2)
    assert e1["kinetic"] == pytest.approx(kinetic, rel=1e-12)
    assert e1["gravity"] < e0["gravity"]  # it fell


def test_catalogues_list_what_the_program_lists(drapelab_exe):
    names = [d["name"] for d in drapelab.integrators()]
    listing = subprocess.run([drapelab_exe, "integrators"], check=True, capture_output=True,
                             text=True).stdout
    assert names and all(name in listing for name in names)
    assert {"leapfrog", "implicit-euler"} <= set(names)
    assert all(t["name"] in listing for t in drapelab.tables())
    fabrics = subprocess.run([drapelab_exe, "fabrics", "--json"], check=True, capture_output=True,
                             text=True).stdout
    import json
    assert drapelab.fabrics() == json.loads(fabrics)


def test_experiment_runs_the_plan_and_returns_its_results(tmp_path):
    # A 3 x 3 cloth from one pin, two steps swept (tests/analysis/ensemble_statistics_check.py).
    (tmp_path / "cloth.json").write_text(json.dumps({
        "cloth": {"rows": 3, "cols": 3, "spacing": 0.02, "origin": [0, 1.4, 0],
                  "particle_mass": 0.001, "k_structural": 20},
        "pins": [[0, 0]], "dummy": None, "integrator": {"name": "leapfrog", "dt": 0.001},
        "duration": 0.05}))
    (tmp_path / "exp.json").write_text(json.dumps({
        "name": "tiny", "question": "Does drapelab.experiment run the plan?",
        "scenes": ["cloth.json"], "sweep": {"integrator.dt": [0.001, 0.0005]}}))
    results = drapelab.experiment(tmp_path / "exp.json", tmp_path / "out", jobs=2)
    assert results["status"].tolist() == ["ok", "ok"]
    assert sorted(zip(results["integrator.dt"], results["steps"])) == [(0.0005, 100), (0.001, 50)]
    # Each run is the run of its scene: the same final state as a Simulation of it.
    sim = drapelab.Simulation(drapelab.load_scene(tmp_path / "cloth.json"))
    sim.advance(0.05)
    run_dir = tmp_path / "out" / results.loc[results["integrator.dt"] == 0.001, "run_dir"].iloc[0]
    state = np.loadtxt(run_dir / "state.csv", delimiter=",", skiprows=1)  # index,row,col,x,y,z,...
    np.testing.assert_array_equal(state[:, 3:6], sim.positions)  # written to round-trip
