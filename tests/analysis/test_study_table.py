"""The study's one table (analysis/drapeanalysis/study_table.py) on synthetic experiment folders:
its cells against the Student-t interval written out, its rows' names from the runs' resolved
keys, and which experiment a row's cells come from."""
import contextlib
import io
import json
import math
import tempfile
import unittest
from pathlib import Path

import pandas as pd

import runfolder  # noqa: F401 (makes drapeanalysis importable)
from drapeanalysis import study_table

# The 97.5 % quantiles of Student's t with 4 and 2 degrees of freedom (tables: 2.7764, 4.3027).
T_975_4 = 2.7764451051977987
T_975_2 = 4.302652729749464

XPBD = {"name": "xpbd", "dt": 0.0333333, "substeps": 80, "iterations": 1}
PD_10 = {"name": "projective-dynamics", "dt": 0.0333333, "iterations": 10}
PD_50 = {"name": "projective-dynamics", "dt": 0.0333333, "iterations": 50}
LEAPFROG = {"name": "leapfrog", "dt": 0.0005}
REFERENCE = {"name": "leapfrog", "dt": 2e-5}


def write_experiment(root, name, runs):
    """An experiment folder: experiment.json with its name, metrics.csv with a row per run and
    runs/<id>/summary.json with the run's status and integrator_options. `runs`: dicts with
    options, scene, status, is_reference and metric values (m, s, J)."""
    folder = Path(root) / name
    rows = []
    for k, run in enumerate(runs):
        run_dir = f"runs/run{k}"
        (folder / run_dir).mkdir(parents=True)
        (folder / run_dir / "summary.json").write_text(json.dumps(
            {"status": run.get("status", "ok"), "integrator_options": run["options"]}))
        rows.append({"scene": f"../scenes/{run.get('scene', 'combination4_hold_release_attach')}.json",
                     "status": run.get("status", "ok"), "is_reference": run.get("is_reference", False),
                     "run_dir": run_dir, "sim_time": 2.5, "energy_initial": 0.25,
                     **{key: value for key, value in run.items()
                        if key not in ("options", "scene", "status", "is_reference")}})
    pd.DataFrame(rows).to_csv(folder / "metrics.csv", index=False)
    (folder / "experiment.json").write_text(json.dumps({"experiment": {"name": name}}))
    return folder


def ensemble(options, costs, **metrics):
    """One run per cost (CPU seconds over 2.5 s simulated), the same other metrics each."""
    return [{"options": options, "cpu_seconds": c, **metrics} for c in costs]


class SettingTest(unittest.TestCase):
    def test_a_setting_names_the_step_and_the_work_per_step(self):
        self.assertEqual(study_table.setting(XPBD), "xpbd 1/30 s, 80 substeps")
        self.assertEqual(study_table.setting({**XPBD, "iterations": 2}), "xpbd 1/30 s, 80 substeps x 2 sweeps")
        self.assertEqual(study_table.setting(PD_50), "projective-dynamics 1/30 s, 50 iterations")
        self.assertEqual(study_table.setting({"name": "implicit-euler", "dt": 0.01, "linear_tolerance": 1e-3}),
                         "implicit-euler 10 ms, CG 0.001")
        self.assertEqual(study_table.setting({"name": "implicit-euler", "dt": 0.01, "solve": "converged"}),
                         "implicit-euler 10 ms, converged")
        self.assertEqual(study_table.setting({"name": "arkode-dirk", "dt": 0.0333333, "table": "ARKODE_SDIRK_2_1_2",
                                              "nonlinear_solver": "line-search"}),
                         "arkode-dirk 1/30 s, SDIRK_2_1_2, line-search")
        self.assertEqual(study_table.setting({"name": "bdf2", "dt": 0.0333333, "linearise_about": "predictor"}),
                         "bdf2 1/30 s, from the predictor")
        self.assertEqual(study_table.setting({"name": "bdf2", "dt": 0.0333333}), "bdf2 1/30 s, from y_n")
        self.assertEqual(study_table.setting({"name": "bdf2", "dt": 0.0333333, "solve": "converged",
                                              "linearise_about": "predictor"}), "bdf2 1/30 s, converged")
        self.assertEqual(study_table.setting(REFERENCE, is_reference=True), "reference: leapfrog 0.02 ms")


class CellTest(unittest.TestCase):
    def runs(self, values, statuses=None):
        statuses = statuses or ["ok"] * len(values)
        return pd.DataFrame({"x": values, "status": statuses})

    def test_a_cell_is_the_mean_and_the_student_t_half_width_with_n(self):
        values = [1.0, 2.0, 3.0, 4.0, 10.0]
        mean = sum(values) / 5
        std = math.sqrt(sum((v - mean) ** 2 for v in values) / 4)
        half = T_975_4 * std / math.sqrt(5)
        self.assertEqual(study_table.cell(self.runs(values), "x", 1e3),
                         f"{mean * 1e3:.3g} +- {half * 1e3:.2g} (5)")

    def test_only_finished_runs_with_a_value_count(self):
        cell = study_table.cell(self.runs([1.0, math.nan, 5.0], ["ok", "ok", "diverged"]), "x", 1.0)
        self.assertEqual(cell, "1 (1)")

    def test_no_finished_run_says_how_many_stopped(self):
        self.assertEqual(study_table.cell(self.runs([1.0, 2.0], ["diverged"] * 2), "x", 1.0), "diverged (2 of 2)")
        self.assertEqual(study_table.cell(self.runs([1.0, 2.0], ["diverged", "failed"]), "x", 1.0), "failed (2 of 2)")
        self.assertEqual(study_table.cell(self.runs([math.nan] * 2), "x", 1.0), "–")
        self.assertEqual(study_table.cell(None, "x", 1.0), "–")

    def test_real_time_reads_the_costs_interval_against_one(self):
        def runs(costs):
            return pd.DataFrame({"cost": costs, "status": ["ok"] * len(costs)})
        self.assertEqual(study_table.real_time(runs([0.5, 0.6, 0.55])), "yes")
        self.assertEqual(study_table.real_time(runs([1.5, 1.6, 1.55])), "no")
        self.assertEqual(study_table.real_time(runs([0.9, 1.1, 0.95, 1.05])), "at the line")


class TableTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        root = self.tmp.name
        hold = {"vibration_rms_after_hold": 0.011, "restart_error_after_hold": 0.001,
                "energy_final": 0.24}
        self.main = write_experiment(root, "main", ensemble(LEAPFROG, [0.1] * 3, **hold)
                                     + ensemble(PD_10, [0.05] * 3, **hold)
                                     + ensemble(PD_10, [9.0] * 3, scene="combination1_hold_release", **hold)
                                     + ensemble(REFERENCE, [2.0] * 3, is_reference=True, **hold))
        self.regimes = write_experiment(root, "regimes", ensemble(PD_10, [7.0] * 3, **hold)
                                        + ensemble(PD_50, [0.25] * 3, **hold))
        self.large = write_experiment(root, "large", ensemble(PD_50, [0.6, 0.62, 0.58], restart_error_after_hold=0.03)
                                      + ensemble(XPBD, [4.0, 4.5, 4.25], restart_error_after_hold=0.02)
                                      + [{"options": LEAPFROG, "cpu_seconds": 0.001, "status": "diverged"}] * 2)

    def tearDown(self):
        self.tmp.cleanup()

    def rows(self):
        text = study_table.table([study_table.read_runs(self.main, "combination4_hold_release_attach"),
                                  study_table.read_runs(self.regimes, "combination4_hold_release_attach")],
                                 study_table.read_runs(self.large))
        lines = text.splitlines()
        head = [c.strip() for c in lines[0].strip("|").split("|")]
        return [dict(zip(head, (c.strip() for c in line.strip("|").split("|")))) for line in lines[2:]]

    def test_a_row_per_setting_in_the_studys_order_the_reference_last(self):
        self.assertEqual([r["method and setting"] for r in self.rows()],
                         ["leapfrog 0.5 ms", "xpbd 1/30 s, 80 substeps", "projective-dynamics 1/30 s, 10 iterations",
                          "projective-dynamics 1/30 s, 50 iterations", "reference: leapfrog 0.02 ms"])

    def test_the_first_small_experiment_with_a_setting_gives_its_cells(self):
        def mean_and_n(cell):
            return float(cell.split()[0]), cell.split()[-1]
        rows = {r["method and setting"]: r for r in self.rows()}
        pd10 = rows["projective-dynamics 1/30 s, 10 iterations"]
        # 0.05 s over 2.5 s in the main job's combination 4, not the regimes' 7 s or combination 1's 9 s.
        self.assertEqual(mean_and_n(pd10["cost 20 x 20 [CPU s/s]"]), (0.02, "(3)"))
        self.assertEqual(pd10["from"], "main")
        pd50 = rows["projective-dynamics 1/30 s, 50 iterations"]
        self.assertEqual(mean_and_n(pd50["cost 20 x 20 [CPU s/s]"]), (0.1, "(3)"))
        self.assertEqual(mean_and_n(pd50["vibration after hold [mm]"]), (11.0, "(3)"))
        self.assertEqual(mean_and_n(pd50["energy change E(end) - E(0) [mJ]"]), (-10.0, "(3)"))
        self.assertEqual(pd50["from"], "regimes, large")

    def test_the_large_cloths_cells_and_real_time(self):
        rows = {r["method and setting"]: r for r in self.rows()}
        pd50, xpbd, leapfrog = (rows["projective-dynamics 1/30 s, 50 iterations"], rows["xpbd 1/30 s, 80 substeps"],
                                rows["leapfrog 0.5 ms"])
        # 0.24, 0.248, 0.232 CPU s/s: mean 0.24, std 0.008.
        self.assertEqual(pd50["cost 64 x 64 [CPU s/s]"], f"0.24 +- {T_975_2 * 0.008 / math.sqrt(3):.2g} (3)")
        self.assertEqual(pd50["real time at 64 x 64"], "yes")
        self.assertEqual(float(pd50["same at 64 x 64 [mm]"].split()[0]), 30.0)
        self.assertEqual(xpbd["real time at 64 x 64"], "no")
        self.assertEqual(xpbd["cost 20 x 20 [CPU s/s]"], "–")
        self.assertEqual(xpbd["from"], "large")
        self.assertEqual(leapfrog["cost 64 x 64 [CPU s/s]"], "diverged (2 of 2)")
        self.assertEqual(leapfrog["real time at 64 x 64"], "–")

    def test_the_tables_by_scene_have_a_column_per_scene_and_only_measured_metrics(self):
        text = study_table.scene_tables(study_table.read_runs(self.main))
        titles = [line for line in text.splitlines() if line.endswith(":")]
        # The runs have a hold's vibration and restart error, energy and cost, nothing else.
        self.assertEqual(titles, ["Vibration after the hold [mm]:", "Restart error one frame after the hold [mm]:",
                                  "Energy change E(end) - E(0) [mJ]:", "Cost [CPU s of stepping per simulated s]:"])
        cost = text.split("Cost [CPU s of stepping per simulated s]:")[1].strip().splitlines()
        self.assertEqual(cost[0], "| method | paper-like 4 | paper-like 1 |")
        pd10 = next(line for line in cost if line.startswith("| projective-dynamics"))
        cells = [c.strip() for c in pd10.strip("|").split("|")]
        # 0.05 s and 9 s over 2.5 s simulated, each in its own scene's column.
        self.assertEqual([float(c.split()[0]) for c in cells[1:]], [0.02, 3.6])
        # Leap-frog ran combination 4 only: combination 1's cell is a dash.
        self.assertTrue(cost[2].startswith("| leapfrog 0.5 ms | 0.04 +- ") and cost[2].endswith("| – |"), cost[2])

    def test_one_scene_gives_one_table_with_a_column_per_metric(self):
        lines = study_table.scene_tables(study_table.read_runs(self.large)).splitlines()
        self.assertEqual(lines[0], "| method | Restart error one frame after the hold [mm] | "
                                   "Cost [CPU s of stepping per simulated s] |")
        rows = {line.split("|")[1].strip(): [c.strip() for c in line.strip("|").split("|")[1:]] for line in lines[2:]}
        self.assertEqual(rows["leapfrog 0.5 ms"], ["diverged (2 of 2)", "diverged (2 of 2)"])
        self.assertEqual(float(rows["xpbd 1/30 s, 80 substeps"][0].split()[0]), 20.0)
        self.assertEqual(float(rows["xpbd 1/30 s, 80 substeps"][1].split()[0]), 1.7)

    def test_a_scenes_heading_names_its_regime_and_combination(self):
        self.assertEqual(study_table.scene_heading("combination1_hold_release"), "paper-like 1")
        self.assertEqual(study_table.scene_heading("combination4_hold_release_attach_knit"), "knit 4")
        self.assertEqual(study_table.scene_heading("combination1_hold_release_woven"), "woven 1")
        self.assertEqual(study_table.scene_heading("drape_dress_form"), "drape_dress_form")

    def test_a_missing_experiment_exits_with_2(self):
        with contextlib.redirect_stderr(io.StringIO()) as err:
            code = study_table.main(["--small", str(Path(self.tmp.name) / "nowhere"), "--large", str(self.large)])
        self.assertEqual(code, 2)
        self.assertIn("nowhere", err.getvalue())


if __name__ == "__main__":
    unittest.main()
