"""The runs table's headings carry units (analysis/drapeanalysis/table_columns.py)."""
import unittest

from drapeanalysis import table_columns

# Counts, a status and its reason (text), and the bisected parameter's own value: no unit of their own.
UNITLESS = {"status", "reason", "steps", "rhs_evals", "stable_value"}


class TableColumnsTest(unittest.TestCase):
    def test_every_metric_column_but_counts_and_status_has_a_unit(self):
        missing = [c for c in table_columns.TABLE_COLUMNS
                   if c not in UNITLESS and c not in table_columns.UNITS]
        self.assertEqual(missing, [])

    def test_a_heading_puts_the_unit_in_brackets(self):
        self.assertEqual(table_columns.heading("wall_seconds"), "wall_seconds [s]")
        self.assertEqual(table_columns.heading("vibration_rms_final"), "vibration_rms_final [mm]")

    def test_a_length_is_shown_in_mm_from_the_m_of_metrics_csv(self):
        self.assertEqual(table_columns.shown_value("vibration_rms_final", 0.0025), 2.5)
        self.assertEqual(table_columns.shown_value("wall_seconds", 0.0025), 0.0025)
        self.assertEqual(table_columns.shown_value("steps", 7), 7)
        self.assertEqual(table_columns.heading("integrator.dt"), "integrator.dt [s]")
        self.assertEqual(table_columns.heading("steps"), "steps")


if __name__ == "__main__":
    unittest.main()
