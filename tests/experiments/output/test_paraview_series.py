"""frames/frames.vtk.series read back with VTK, as ParaView reads it (docs/outputs.md, frames/).

Run by ctest as `paraview_series` with the drapelab executable as its argument: runs the paper's
Figure 4 scene for 1 s (a hold at 0.425 s, a particle in contact) with VTK frames and a trace at
the same interval, then checks every frame's time and point data against trace.csv.
"""
import csv
import json
import os
import subprocess
import sys
import tempfile
import unittest

import vtk

DRAPELAB = os.environ.get("DRAPELAB_EXE", "build/bin/drapelab")
SOURCE_DIR = os.environ.get("DRAPE_SOURCE_DIR", ".")


def point_array(polydata, name):
    array = polydata.GetPointData().GetArray(name)
    if array is None:
        raise AssertionError(f"no point array {name!r}")
    components = array.GetNumberOfComponents()
    return [tuple(array.GetComponent(i, c) for c in range(components))
            for i in range(array.GetNumberOfTuples())]


class ParaViewSeries(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.out = os.path.join(cls.tmp.name, "fig4")
        scene = os.path.join(SOURCE_DIR, "experiments", "scenes", "fig4_attach.json")
        subprocess.run([DRAPELAB, "run", scene, "--out", cls.out, "--quiet",
                        "--set", "duration=1.0", "--set", "output.vtk_interval=0.1",
                        "--set", "output.trace_interval=0.1"], check=True)
        with open(os.path.join(cls.out, "frames", "frames.vtk.series")) as f:
            cls.series = json.load(f)
        with open(os.path.join(cls.out, "summary.json")) as f:
            cls.summary = json.load(f)
        # trace.csv rows by (time as written, particle): the same frame times as the VTK frames.
        cls.trace = {}
        with open(os.path.join(cls.out, "trace.csv")) as f:
            for row in csv.DictReader(f):
                cls.trace.setdefault(float(row["t"]), {})[int(row["index"])] = row

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def read_frame(self, name):
        reader = vtk.vtkPolyDataReader()
        reader.SetFileName(os.path.join(self.out, "frames", name))
        reader.Update()
        return reader.GetOutput()

    def test_series_lists_every_frame_at_its_simulated_time(self):
        self.assertEqual(self.series["file-series-version"], "1.0")
        files = self.series["files"]
        hold = [e["t"] for e in self.summary["events"] if e["type"] == "hold"]
        self.assertEqual(len(hold), 1)
        # 0, 0.1, ..., 1.0 and the frame right after the hold event.
        self.assertEqual(len(files), 12)
        self.assertEqual([f["name"] for f in files], [f"frame_{i:05d}.vtk" for i in range(12)])
        times = [f["time"] for f in files]
        self.assertEqual(times, sorted(times))
        self.assertIn(hold[0], times)
        self.assertAlmostEqual(times[-1], 1.0, delta=1e-12)
        self.assertEqual(sorted(self.trace), times)
        for f in files:
            field = self.read_frame(f["name"]).GetFieldData().GetArray("TIME")
            self.assertEqual(field.GetValue(0), f["time"])

    def test_point_data_matches_the_trace(self):
        hold = next(e for e in self.summary["events"] if e["type"] == "hold")
        contacts = 0
        for f in self.series["files"]:
            frame = self.read_frame(f["name"])
            rows = self.trace[f["time"]]
            n = frame.GetNumberOfPoints()
            self.assertEqual(n, self.summary["particles"])
            velocity = point_array(frame, "velocity")
            fixed = point_array(frame, "fixed")
            held = point_array(frame, "held")
            contact = point_array(frame, "contact")
            for i in range(n):
                row = rows[i]
                for c, key in enumerate(("vx", "vy", "vz")):
                    self.assertEqual(velocity[i][c], float(row[key]))
                self.assertEqual(fixed[i][0], int(row["fixed"]))
                self.assertEqual(contact[i][0], int(row["contact"]))
                expect_held = int(i == hold["particle"] and f["time"] >= hold["t"])
                self.assertEqual(held[i][0], expect_held, (f["time"], i))
            contacts += sum(1 for c in contact if c[0] >= 0)
        # The scene has a particle in contact: the array is not all -1.
        self.assertGreater(contacts, 0)


if __name__ == "__main__":
    if len(sys.argv) > 1:
        DRAPELAB = sys.argv.pop(1)
    unittest.main()
