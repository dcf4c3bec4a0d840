"""The order integrators take their colours in (drapeanalysis/integrator_order.py): the names
`drapelab integrators --json` lists, in registry order, then the table's others sorted; any
failure of that program leaves the sorted names alone."""
import tempfile
import unittest
from pathlib import Path

from runfolder import ANALYSIS_DIR  # noqa: F401  (makes drapeanalysis importable)
from drapeanalysis.integrator_order import declared_integrators, integrator_order  # noqa: E402


class IntegratorOrderTest(unittest.TestCase):
    def setUp(self):
        self._tmp = tempfile.TemporaryDirectory()

    def tearDown(self):
        self._tmp.cleanup()

    def program(self, script):
        """A stand-in for drapelab: a shell script that runs `script`."""
        program = Path(self._tmp.name) / "drapelab"
        program.write_text("#!/bin/sh\n" + script + "\n")
        program.chmod(0o755)
        return program

    def test_colour_order_is_the_registry_order_else_the_table_names_sorted(self):
        rows = [{"integrator": "vbd"}, {"integrator": "leapfrog"}, {"integrator": "bdf2"}]
        self.assertEqual(integrator_order(None, rows), ["bdf2", "leapfrog", "vbd"])
        program = self.program("echo '[{\"name\": \"leapfrog\"}, {\"name\": \"xpbd\"}, {\"name\": \"vbd\"}]'")
        self.assertEqual(integrator_order(program, rows), ["leapfrog", "xpbd", "vbd", "bdf2"])
        self.assertEqual(integrator_order(Path(self._tmp.name) / "missing", rows), ["bdf2", "leapfrog", "vbd"])

    def test_the_program_is_asked_for_the_json_list(self):
        program = self.program('[ "$1 $2" = "integrators --json" ] && echo \'[{"name": "leapfrog"}]\'')
        self.assertEqual(declared_integrators(program), ["leapfrog"])

    def test_a_program_that_fails_or_prints_no_list_declares_nothing(self):
        for script in ("exit 3",                                    # an error
                       "echo 'leapfrog xpbd'",                      # not JSON (an older build's text)
                       "echo '{\"name\": \"leapfrog\"}'",           # an object, not a list
                       "echo '[\"leapfrog\"]'"):                    # a list of no declarations
            with self.subTest(script):
                self.assertEqual(declared_integrators(self.program(script)), [])
        # Entries without a string name are skipped, the others kept in order.
        program = self.program('echo \'[{"name": "vbd"}, {"name": 3}, {}, {"name": "bdf2"}]\'')
        self.assertEqual(declared_integrators(program), ["vbd", "bdf2"])

    def test_rows_without_an_integrator_add_no_name(self):
        rows = [{"integrator": "xpbd"}, {"integrator": None}, {}, {"integrator": ""}, {"integrator": "xpbd"}]
        self.assertEqual(integrator_order(None, rows), ["xpbd"])


if __name__ == "__main__":
    unittest.main()
