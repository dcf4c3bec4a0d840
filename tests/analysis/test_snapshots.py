"""The snapshot figures' geometry and choices (drapeanalysis/snapshots.py, docs/analysis.md
Figures): the cloth's cells and the object's rings as quads, the shading in closed form, the
instants shown and each run's own frame of them, the runs drawn per scene."""
import unittest

import numpy as np
import pandas as pd

import runfolder
from drapeanalysis import snapshots


def grid(rows, cols):
    """A flat rows x cols grid in the plane z = 0, x = col, y = -row, row-major."""
    r, c = np.divmod(np.arange(rows * cols), cols)
    return np.stack([c, -r, np.zeros(rows * cols)], axis=1).astype(float)


class GeometryTest(unittest.TestCase):
    def test_cloth_cells_go_round_each_grid_square(self):
        quads = snapshots.cloth_quads(grid(3, 4), 3, 4)
        self.assertEqual(quads.shape, (2 * 3, 4, 3))
        # Cell (1, 2): particles 6, 7, 11, 10, its corners in order round the square.
        np.testing.assert_array_equal(quads[1 * 3 + 2], grid(3, 4)[[6, 7, 11, 10]])

    def test_object_rings_of_one_size_make_a_band_of_quads(self):
        angle = np.tile(np.arange(4) * np.pi / 2, 3)
        ring = np.repeat(np.arange(3), 4)
        dummy = pd.DataFrame({"section": ring, "point": np.tile(np.arange(4), 3), "x": np.cos(angle),
                              "y": ring.astype(float), "z": np.sin(angle)})
        quads = snapshots.object_quads(dummy.iloc[::-1])  # any row order
        self.assertEqual(quads.shape, (2 * 4, 4, 3))
        # Between rings 0 and 1, the last point joins the first: the ring closes.
        np.testing.assert_allclose(quads[3], [[0, 0, -1], [1, 0, 0], [1, 1, 0], [0, 1, -1]], atol=1e-15)
        self.assertIsNone(snapshots.object_quads(dummy.iloc[:-1]), "rings of different sizes")
        self.assertIsNone(snapshots.object_quads(dummy[dummy.section == 0]), "one ring")

    def test_shading_is_the_cosine_to_the_light_above_a_floor(self):
        facing = snapshots.cloth_quads(grid(2, 2), 2, 2)  # normal along z, the front view's depth
        light = np.array([-0.3, 0.6, 1.0]) / np.linalg.norm([-0.3, 0.6, 1.0])
        rgb = np.array([1.0, 0.5, 0.0])
        np.testing.assert_allclose(snapshots.shade(facing, rgb, "front"),
                                   [(0.35 + 0.65 * light[2]) * rgb], rtol=1e-14)
        flipped = facing[:, ::-1]  # the other side: shaded alike (two-sided)
        np.testing.assert_allclose(snapshots.shade(flipped, rgb, "front"), snapshots.shade(facing, rgb, "front"))
        degenerate = np.zeros((1, 4, 3))
        np.testing.assert_allclose(snapshots.shade(degenerate, rgb, "side"), [0.35 * rgb])

    def test_a_grid_that_is_not_the_traces_names_both_files(self):
        run = runfolder.ANALYSIS_DIR / "run"
        trace = {"x": np.zeros((2, 12, 3))}
        self.assertEqual(snapshots.cloth_grid(run, {"scene": {"cloth": {"rows": 3, "cols": 4}}}, trace), (3, 4))
        for cloth in ({"rows": 4, "cols": 4}, {"rows": True, "cols": 12}, {"rows": 3}):
            with self.subTest(cloth), self.assertRaises(ValueError) as error:
                snapshots.cloth_grid(run, {"scene": {"cloth": cloth}}, trace)
            self.assertIn(f"{run / 'summary.json'}: scene.cloth.rows x cols = ", str(error.exception))
            self.assertTrue(str(error.exception).endswith(f"but {run / 'trace.csv'} has 12 particles a frame"))


class InstantsTest(unittest.TestCase):
    SUMMARY = {"events": [{"type": "hold", "t": 0.3}, {"type": "ignored", "t": 0.35},
                          {"type": "release", "t": 0.6}, {"type": "hold", "t": 0.9}]}

    def test_each_manipulation_with_its_occurrence_then_the_end(self):
        self.assertEqual(snapshots.event_list(self.SUMMARY),
                         [("hold", 0, 0.3), ("release", 0, 0.6), ("hold", 1, 0.9)])
        self.assertEqual(snapshots.instants(self.SUMMARY, 2.0),
                         [("hold", 0, 0.3), ("release", 0, 0.6), ("hold", 1, 0.9), ("end", 0, 2.0)])
        many = {"events": [{"type": "map", "t": 0.1 * k} for k in range(10)]}
        shown = snapshots.instants(many, 2.0)
        self.assertEqual(len(shown), snapshots.MAX_INSTANTS)
        self.assertEqual(shown[-1], ("end", 0, 2.0))

    def test_frame_at_is_the_last_frame_at_or_before(self):
        trace = {"t": np.array([0.0, 0.1, 0.2, 0.3])}
        self.assertEqual(snapshots.frame_at(trace, 0.2), 2)
        self.assertEqual(snapshots.frame_at(trace, 0.25), 2)
        self.assertEqual(snapshots.frame_at(trace, 0.3), 3)
        self.assertIsNone(snapshots.frame_at(trace, 0.31), "the trace ends before")

    def test_a_snapshot_of_an_event_is_the_runs_own_and_none_for_a_run_without_it(self):
        # The instants come from the first run's events; a run that never held has no "hold"
        # frame: another run's hold time would show another instant under the hold's name.
        trace = {"t": np.array([0.0, 0.5, 0.52, 1.0])}
        held = {"events": [{"type": "hold", "t": 0.52}, {"type": "ignored", "t": 0.7}]}
        self.assertEqual(snapshots.run_frame(trace, held, "hold", 0), 2)
        self.assertEqual(snapshots.run_frame(trace, held, "end", 0), 3)
        with self.assertRaises(KeyError):
            snapshots.run_frame(trace, {"events": [{"type": "ignored", "t": 0.5}]}, "hold", 0)


class MethodsTest(unittest.TestCase):
    def test_the_reference_then_each_integrator_at_its_smallest_step(self):
        rows = [{"id": "ie", "integrator": "implicit-euler", "integrator.dt": 0.01},
                {"id": "lf2", "integrator": "leapfrog", "integrator.dt": 2e-4},
                {"id": "ref", "integrator": "leapfrog", "integrator.dt": 1e-5, "is_reference": True},
                {"id": "lf1", "integrator": "leapfrog", "integrator.dt": 1e-4},
                {"id": "ie-fine", "integrator": "implicit-euler", "integrator.dt": 0.001}]
        self.assertEqual([r["id"] for r in snapshots.methods(rows)], ["ref", "lf1", "ie-fine"])
        self.assertEqual(snapshots.method_name(rows[2]), "leapfrog\ndt=1e-05 (ref.)")
        self.assertEqual(snapshots.method_name({"integrator": "vbd", "dt": 0.002}), "vbd\ndt=0.002")

    def test_at_most_max_methods(self):
        rows = [{"integrator": f"m{k}", "integrator.dt": 0.001} for k in range(snapshots.MAX_METHODS + 3)]
        self.assertEqual(len(snapshots.methods(rows)), snapshots.MAX_METHODS)


if __name__ == "__main__":
    unittest.main()
