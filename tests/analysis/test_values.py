"""values.py: each check lets a good value through unchanged and refuses a bad one with a
ValueError naming the file and the field, or the row and column, of the first bad value."""
import math
import unittest

import numpy as np

from drapeanalysis import values


class FiniteNumberTest(unittest.TestCase):
    def test_numbers_pass_as_floats(self):
        self.assertEqual(values.finite_number(3, "s.json", "dt"), 3.0)
        self.assertIsInstance(values.finite_number(3, "s.json", "dt"), float)
        self.assertEqual(values.finite_number(-2.5e-3, "s.json", "dt"), -2.5e-3)

    def test_anything_else_names_file_field_and_value(self):
        for bad, quoted in ((None, "null"), ("1", '"1"'), (True, "true"), (math.nan, "NaN"),
                            (math.inf, "Infinity"), ([1], "[1]")):
            with self.assertRaises(ValueError) as caught:
                values.finite_number(bad, "s.json", "dt")
            self.assertEqual(str(caught.exception),
                             f"s.json: dt: expected a finite number, got {quoted}")

    def test_long_values_are_cut(self):
        self.assertEqual(values.shown("x" * 100, limit=10), '"xxxxxxxxx...')
        self.assertEqual(values.shown([1, 2]), "[1, 2]")


class CheckIncreasingTest(unittest.TestCase):
    def test_increasing_times_pass(self):
        values.check_increasing("e.csv", [0.0, 1e-3, 2e-3])
        values.check_increasing("e.csv", [0.5])

    def test_the_first_repeated_time_is_named_by_row(self):
        # t[2] repeats t[1]: the third data row, the fourth line counting the header.
        with self.assertRaises(ValueError) as caught:
            values.check_increasing("e.csv", [0.0, 0.1, 0.1, 0.05])
        self.assertEqual(str(caught.exception),
                         "e.csv: row 3, column t: t = 0.10000000000000001 is not after the time "
                         "before it, t = 0.10000000000000001 (times must increase)")

    def test_nan_is_not_after_anything_and_where_names_the_place(self):
        with self.assertRaises(ValueError) as caught:
            values.check_increasing("x.npy", [0.0, math.nan], where=lambda k: f"frame {k}")
        self.assertTrue(str(caught.exception).startswith("x.npy: frame 1: t = nan"))


class FlagsStatusArrayTest(unittest.TestCase):
    def test_flags_are_zero_or_one(self):
        values.check_flags("c.npy", np.array([[0, 1], [1, 0]]), lambda k: f"value {k}")
        with self.assertRaises(ValueError) as caught:
            values.check_flags("c.npy", np.array([[0, 1], [2, 0.5]]), lambda k: f"value {k}")
        self.assertEqual(str(caught.exception), "c.npy: value 2: 2, expected 0 or 1")

    def test_status_must_be_one_allowed(self):
        for status in values.RESULT_STATUSES:
            values.check_status(status, values.RESULT_STATUSES, "results.json", "runs[0].status")
        for bad in ("crashed", 1, None):
            with self.assertRaises(ValueError) as caught:
                values.check_status(bad, values.RUN_STATUSES, "summary.json", "status")
            self.assertTrue(str(caught.exception).startswith(
                "summary.json: status: expected one of ok, diverged, failed, got "))

    def test_first_non_finite_value_is_named_by_index(self):
        values.check_finite_array("x.npy", np.zeros((2, 3)))
        array = np.zeros((2, 3))
        array[1, 2] = np.inf
        array[1, 0] = np.nan
        with self.assertRaises(ValueError) as caught:
            values.check_finite_array("x.npy", array)
        self.assertEqual(str(caught.exception), "x.npy: index [1, 0]: not a finite number (nan)")

    def test_json_type_names(self):
        self.assertEqual([values.json_type(v) for v in ("a", 1, 1.0, [], {}, True, None)],
                         ["a string", "an integer", "a number", "a list", "an object",
                          "true or false", "null"])


if __name__ == "__main__":
    unittest.main()
