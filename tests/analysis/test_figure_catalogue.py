"""The report's figure catalogue (drapeanalysis/figure_catalogue.py): every figure has a caption
and the metrics that ask for it, and the metric names are those drapelab accepts
(known_metrics(), docs/experiments.md)."""
import unittest

import runfolder  # noqa: F401  (puts analysis/ on the path)
from drapeanalysis.figure_catalogue import CAPTIONS, FIGURE_METRIC, KNOWN_METRICS, figure_metrics

# The names an experiment's `metrics` may hold: drapelab's known_metrics(), which refuses others.
DRAPELAB_METRICS = {"energy_drift", "vibration", "attach_error", "mapping_error", "work_precision",
                    "stable_dt", "restart_error", "snapshots"}
ARROW = " An arrow at a bar's foot: its 95 % interval reaches 0, which a log axis cannot show"


class FigureCatalogueTest(unittest.TestCase):
    def test_every_figure_has_a_caption_and_its_metrics(self):
        self.assertEqual(set(CAPTIONS), set(FIGURE_METRIC))
        for name in CAPTIONS:
            with self.subTest(name):
                self.assertIsInstance(figure_metrics(name), tuple)
                self.assertTrue(set(figure_metrics(name)) <= KNOWN_METRICS)
                self.assertTrue(CAPTIONS[name].rstrip().endswith("."), CAPTIONS[name][-40:])

    def test_a_figure_needs_one_metric_or_all_of_several(self):
        self.assertEqual(figure_metrics("energy_vs_time"), ("energy_drift",))
        self.assertEqual(figure_metrics("accuracy_cost"), ("restart_error", "vibration"))
        with self.assertRaises(KeyError):
            figure_metrics("no_such_figure")

    def test_known_metrics_are_drapelabs(self):
        self.assertEqual(KNOWN_METRICS, DRAPELAB_METRICS)

    def test_log_axis_figures_explain_the_arrow_once(self):
        with_arrow = {name for name, caption in CAPTIONS.items() if ARROW in caption}
        self.assertEqual(with_arrow, {"work_precision", "accuracy_cost", "restart_error_vs_horizon",
                                      "attach_error_vs_iterations", "attach_error_vs_solver_work",
                                      "attach_error_vs_time", "vibration_vs_dt", "contact_switch_vs_dt"})
        for name in with_arrow:
            self.assertEqual(CAPTIONS[name].count(ARROW), 1, name)
        self.assertTrue(CAPTIONS["vibration_vs_dt"].endswith("; series at the same x are drawn slightly apart."))
        self.assertTrue(CAPTIONS["work_precision"].endswith("cannot show."))


if __name__ == "__main__":
    unittest.main()
