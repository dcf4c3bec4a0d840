"""The report's 3-D viewer pages (drapeanalysis/viewer_pages.py, docs/analysis.md Viewer pages),
with a stand-in for drapelab that records its arguments: a page per run with frames, a note for
each run without, a side-by-side page per scene, and drapelab's failures told apart."""
import unittest

import runfolder
from drapeanalysis import viewer_pages
from drapeanalysis.fileio import OutputError


class SideBySideTest(unittest.TestCase):
    def test_side_by_side_pairs_leapfrog_with_an_implicit_method_at_their_smallest_steps(self):
        rows = [{"id": "ref", "integrator": "leapfrog", "integrator.dt": 1e-5, "is_reference": True},
                {"id": "lf2", "integrator": "leapfrog", "integrator.dt": 2e-4},
                {"id": "lf1", "integrator": "leapfrog", "integrator.dt": 1e-4},
                {"id": "dirk", "integrator": "arkode-dirk", "integrator.dt": 1e-3},
                {"id": "ie2", "integrator": "implicit-euler", "integrator.dt": 1e-2},
                {"id": "ie1", "integrator": "implicit-euler", "integrator.dt": 2e-3}]
        self.assertEqual([r["id"] for r in viewer_pages.side_by_side(rows)], ["lf1", "ie1"])
        # One kind only: the reference and the finest run; a single run: no page.
        self.assertEqual([r["id"] for r in viewer_pages.side_by_side(rows[:3])], ["ref", "lf1"])
        self.assertEqual(viewer_pages.side_by_side(rows[1:2]), [])


class WritePagesTest(runfolder.RunFolderTest):
    def setUp(self):
        super().setUp()
        self.rows = runfolder.write_experiment(self.directory, scenes=("scenes/a.json",))
        self.out = self.directory / "report"
        self.out.mkdir()
        self.calls = self.directory / "calls.txt"

    def drapelab(self, status=0, message=""):
        """A drapelab that appends its arguments to calls.txt and writes the --out page (its
        folder made as `drapelab view` does), or prints `message` and exits with `status`."""
        program = self.directory / "drapelab"
        program.write_text(f"#!/bin/sh\necho \"$@\" >> {self.calls}\n"
                           + (f"echo '{message}' >&2\nexit {status}\n" if status else
                              'while [ "$1" != --out ]; do shift; done\nmkdir -p "$(dirname "$2")"\n'
                              'echo page > "$2"\n'))
        program.chmod(0o755)
        return str(program)

    def test_a_page_per_run_and_one_per_scene(self):
        (self.directory / "runs" / "a-0.002" / "trace.csv").unlink()
        extra = {"id": "gone", "run_dir": "runs/gone", "status": "diverged", "scene": "scenes/a.json"}
        links, notes, scenes = viewer_pages.write_pages(self.directory, self.out, self.rows + [extra],
                                                        self.drapelab())
        self.assertEqual(links, {"a-0.001": "view/a-0.001.html"})
        self.assertEqual(notes, {"a-0.002": "no page: no trace.csv (output.trace_interval = 0)",
                                 "gone": "no page: the run did not finish (status diverged)"})
        self.assertEqual(scenes, {}, "one run with frames: no side-by-side page")
        self.assertEqual((self.out / "view" / "a-0.001.html").read_text(), "page\n")
        self.assertEqual(self.calls.read_text().splitlines(),
                         [f"view {self.directory / 'runs' / 'a-0.001'} --out {self.out / 'view' / 'a-0.001.html'}"])

    def test_two_runs_of_a_scene_share_a_page(self):
        links, notes, scenes = viewer_pages.write_pages(self.directory, self.out, self.rows, self.drapelab())
        self.assertEqual(set(links), {"a-0.001", "a-0.002"})
        self.assertEqual(notes, {})
        page, shown = scenes["a"]
        self.assertEqual(page, "view/scenes/a.html")
        self.assertEqual([r["id"] for r in shown], ["a-0.001", "a-0.002"])
        self.assertTrue((self.out / "view" / "scenes" / "a.html").exists())

    def test_a_failed_view_is_a_note_and_a_failed_write_an_error(self):
        links, notes, scenes = viewer_pages.write_pages(self.directory, self.out, self.rows[:1],
                                                        self.drapelab(2, "trace.csv: line 3: bad"))
        self.assertEqual((links, scenes), ({}, {}))
        self.assertEqual(notes, {"a-0.001": "no page: drapelab view failed (trace.csv: line 3: bad)"})
        with self.assertRaises(OutputError) as error:
            viewer_pages.write_pages(self.directory, self.out, self.rows[:1], self.drapelab(4, "disk full"))
        self.assertEqual(str(error.exception),
                         f"{self.out / 'view' / 'a-0.001.html'}: drapelab view failed (disk full)")


if __name__ == "__main__":
    unittest.main()
