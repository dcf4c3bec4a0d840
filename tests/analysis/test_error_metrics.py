"""The mapping error and the error against a reference run of docs/analysis.md, against closed
forms on small synthetic run folders."""
import math
import unittest

import numpy as np

import runfolder
from drapeanalysis import metrics, runfiles


class MappingErrorTest(runfolder.RunFolderTest):
    rows, cols, spacing, delta = 3, 4, 0.1, 0.01

    def scene(self):
        return {"cloth": {"rows": self.rows, "cols": self.cols, "spacing": self.spacing},
                "collision": {"threshold": self.delta}}

    def grid(self, scale, height):
        """The cloth grid, spacing scaled by `scale`, flat at `height`; particle index r * cols + c."""
        r, c = np.divmod(np.arange(self.rows * self.cols), self.cols)
        s = self.spacing * scale
        return np.stack([c * s, np.full(len(r), height), r * s], axis=1)

    def write_dummy(self, run, points):
        runfolder.write_csv(run / "dummy.csv", "index,section,point,x,y,z,nx,ny,nz",
                            [(i, 0, i, *p, 0.0, 1.0, 0.0) for i, p in enumerate(points)])

    def test_uniform_stretch_and_gap(self):
        # Final: spacing stretched 3 %, 2 mm above the threshold. Mapped (trace frame of the map
        # event): squeezed 2 %, 1 mm inside it. Object particles on y = 0 right under both grids
        # (and far away ones), so each particle's nearest distance is its height.
        run = self.make_run()
        runfolder.write_summary(run, [{"t": 0.1, "type": "hold"}, {"t": 0.3, "type": "map"}], self.scene(),
                                sim_time=0.4)
        final = self.grid(1.03, self.delta + 0.002)
        mapped = self.grid(0.98, self.delta - 0.001)
        objects = np.concatenate([final, mapped, [[5.0, 5.0, 5.0], [-3.0, 0.0, 1.0]]])
        objects[:len(final) + len(mapped), 1] = 0.0
        self.write_dummy(run, objects)
        runfolder.write_state(run, final, cols=self.cols)
        # Trace: start, the hold's event frame (another shape), a frame before the map, the map's
        # event frame, a later frame.
        frames = [self.grid(1.0, 1.0), self.grid(1.1, 0.5), self.grid(1.2, 0.4), mapped, self.grid(1.05, 0.2)]
        runfolder.write_trace(run, [0.0, 0.1, 0.2, 0.3, 0.4], np.stack(frames), event=np.array([0, 1, 0, 1, 0]))
        out = metrics.mapping_error(run, runfiles.read_json(run / "summary.json"))
        self.assertClose(out["mapping_gap_mean_final"], 0.002, rel=1e-9)
        self.assertClose(out["mapping_gap_max_final"], 0.002, rel=1e-9)
        self.assertClose(out["mapping_gap_mean_mapped"], 0.001, rel=1e-9)
        self.assertClose(out["mapping_gap_max_mapped"], 0.001, rel=1e-9)
        self.assertClose(out["spring_strain_rms_final"], 0.03, rel=1e-9)
        self.assertClose(out["spring_strain_max_final"], 0.03, rel=1e-9)
        self.assertClose(out["spring_strain_rms_mapped"], 0.02, rel=1e-9)
        self.assertClose(out["spring_strain_max_mapped"], 0.02, rel=1e-9)

    def test_uneven_gap_and_strain(self):
        # Heights delta + g_i; the expected strain counted spring by spring here.
        run = self.make_run()
        runfolder.write_summary(run, [{"t": 0.3, "type": "map"}], self.scene())
        x = self.grid(1.0, 0.0)
        x[:, 0] *= 1.01  # 1 % along the rows
        gaps = 0.001 * np.array([1, -2, 0.5, 3, -1, 0, 2, -0.5, 1.5, -3.5, 0.25, 1])
        x[:, 1] = self.delta + gaps
        objects = x.copy()
        objects[:, 1] = 0.0
        self.write_dummy(run, objects)
        runfolder.write_state(run, x, cols=self.cols)
        strains = []
        for r in range(self.rows):
            for c in range(self.cols):
                for dr, dc in ((0, 1), (1, 0), (1, 1), (1, -1)):
                    if 0 <= r + dr < self.rows and 0 <= c + dc < self.cols:
                        a, b = x[r * self.cols + c], x[(r + dr) * self.cols + c + dc]
                        rest = self.spacing * math.hypot(dr, dc)
                        strains.append((np.linalg.norm(b - a) - rest) / rest)
        self.assertEqual(len(strains), 3 * 3 + 2 * 4 + 2 * 2 * 3)
        strains = np.array(strains)
        out = metrics.mapping_error(run, runfiles.read_json(run / "summary.json"))
        self.assertClose(out["mapping_gap_mean_final"], np.mean(np.abs(gaps)))
        self.assertClose(out["mapping_gap_max_final"], 0.0035)
        self.assertClose(out["spring_strain_rms_final"], math.sqrt(np.mean(strains**2)))
        self.assertClose(out["spring_strain_max_final"], np.max(np.abs(strains)))
        self.assertNotIn("mapping_gap_mean_mapped", out, "no trace.csv")

    def test_strain_by_spring_family(self):
        # Stretched 2 % along the rows (x) and squeezed 1 % along the columns (z): each family
        # has one strain, the diagonals sqrt(1.02^2 + 0.99^2) / sqrt(2) - 1.
        run = self.make_run()
        runfolder.write_summary(run, [{"t": 0.3, "type": "map"}], self.scene())
        x = self.grid(1.0, self.delta)
        x[:, 0] *= 1.02
        x[:, 2] *= 0.99
        objects = x.copy()
        objects[:, 1] = 0.0
        self.write_dummy(run, objects)
        runfolder.write_state(run, x, cols=self.cols)
        out = metrics.mapping_error(run, runfiles.read_json(run / "summary.json"))
        shear = math.hypot(1.02, 0.99) / math.sqrt(2) - 1
        for family, expected in (("along_rows", 0.02), ("along_cols", -0.01), ("shear", shear)):
            self.assertClose(out[f"spring_strain_mean_final_{family}"], expected, rel=1e-9)
            self.assertClose(out[f"spring_strain_rms_final_{family}"], abs(expected), rel=1e-9)

    def test_no_map_event(self):
        run = self.make_run()
        runfolder.write_summary(run, [{"t": 0.3, "type": "hold"}], self.scene())
        self.assertEqual(metrics.mapping_error(run, runfiles.read_json(run / "summary.json")), {})


class ReferenceErrorTest(runfolder.RunFolderTest):
    def test_known_displacements(self):
        # Particle i moved by i mm along x plus a common (3, 4, 0) mm.
        n = 10
        base = np.random.default_rng(1).uniform(-1, 1, (n, 3))
        shift = np.array([0.003, 0.004, 0.0]) + np.outer(np.arange(n), [0.001, 0.0, 0.0])
        runfolder.write_state(self.make_run("ref"), base)
        runfolder.write_state(self.make_run("b"), base + shift)
        for name in ("ref", "b"):
            runfolder.write_summary(self.directory / "runs" / name)
        rows = {"ref": self.row("ref"), "b": self.row("b", reference="ref")}
        out, _ = metrics.run_metrics(self.directory, rows["b"], rows)
        distances = np.hypot(0.003 + 0.001 * np.arange(n), 0.004)
        self.assertClose(out["error_rms"], math.sqrt(np.mean(distances**2)))
        self.assertClose(out["error_max"], math.hypot(0.012, 0.004))
        ref_out, _ = metrics.run_metrics(self.directory, rows["ref"], rows)
        self.assertNotIn("error_rms", ref_out)

    def test_uniform_shift(self):
        base = np.zeros((4, 3))
        a, b = self.make_run("a"), self.make_run("b")
        runfolder.write_state(a, base)
        runfolder.write_state(b, base + [0.0, 0.003, 0.004])
        out = metrics.reference_error(b, a)
        self.assertClose(out["error_rms"], 0.005)
        self.assertClose(out["error_max"], 0.005)

    def test_diverged_run_has_no_error(self):
        a, b = self.make_run("a"), self.make_run("b")
        runfolder.write_state(a, np.zeros((4, 3)))
        self.assertEqual(metrics.reference_error(b, a), {}, "no state.csv after divergence")


if __name__ == "__main__":
    unittest.main()
