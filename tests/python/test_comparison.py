#!/usr/bin/python3
"""gran.comparison: comparison.csv written and read back (quantity, paper, measured, error).

Run: PYTHONPATH=python /usr/bin/python3 tests/python/test_comparison.py (make test does).
"""
import math
import unittest

import numpy as np

import fixtures
from gran import comparison

ROWS = [
    ("theta_P_n1", 1.5, 1.4712345678, 0.0123456),
    ("hottest_slab_z", "7-10", 8.5, 0.5),
    ("fig2_peak", None, np.float64(0.25), None),
    ("alpha_not_in_text", 2, math.nan, None),
    ("powerlaw_valid", 0, 1, None),
]


class ComparisonTest(fixtures.TempDirTest):
    def setUp(self):
        super().setUp()
        self.path = self.dir / "comparison.csv"

    def test_cells_use_the_column_formats_and_leave_none_and_nan_empty(self):
        comparison.write(ROWS, self.path)
        self.assertEqual(self.path.read_text().splitlines(), [
            "quantity,paper,measured,error",
            "theta_P_n1,1.5,1.47123,0.0123",
            "hottest_slab_z,7-10,8.5,0.5",
            "fig2_peak,,0.25,",
            "alpha_not_in_text,2,,",
            "powerlaw_valid,0,1,",
        ])

    def test_a_paper_can_choose_its_precision(self):
        comparison.write(ROWS[:1], self.path, measured="{:.4f}", error="{:.4f}")
        self.assertEqual(self.path.read_text().splitlines()[1], "theta_P_n1,1.5,1.4712,0.0123")

    def test_read_returns_numbers_texts_and_none(self):
        comparison.write(ROWS, self.path)
        rows = comparison.read(self.path)
        self.assertEqual(rows[0], comparison.Row("theta_P_n1", 1.5, 1.47123, 0.0123))
        self.assertEqual(rows[1].paper, "7-10")
        self.assertEqual((rows[2].paper, rows[2].error), (None, None))
        self.assertIsNone(rows[3].measured)

    def test_deviation_counts_standard_errors_from_the_paper(self):
        self.assertAlmostEqual(comparison.deviation(comparison.Row("q", 2.0, 2.3, 0.1)), 3.0)
        self.assertTrue(math.isnan(comparison.deviation(comparison.Row("q", "7-10", 8.0, 0.5))))
        self.assertTrue(math.isnan(comparison.deviation(comparison.Row("q", 1.0, 1.2, None))))

    def test_a_row_agrees_within_two_errors_or_ten_percent_and_within_a_printed_range(self):
        row = comparison.Row
        self.assertTrue(comparison.agrees(row("q", 2.0, 2.19, 0.01)))        # 9.5% off
        self.assertFalse(comparison.agrees(row("q", 2.0, 2.25, 0.01)))       # 12.5%, 25 errors
        self.assertTrue(comparison.agrees(row("q", 2.0, 2.5, 0.3)))          # 1.7 errors
        self.assertTrue(comparison.agrees(row("q", "7-10", 10.5, 0.5)))      # 1 error above
        self.assertFalse(comparison.agrees(row("q", "7-10", 0.5, 0.5)))
        self.assertTrue(comparison.agrees(row("q", "> 3", 3.37, 0.003)))      # a bound
        self.assertFalse(comparison.agrees(row("q", "> 3", 2.9, 0.01)))
        self.assertTrue(comparison.agrees(row("q", "< 1", 1.01, 0.01)))       # 1 error above
        self.assertFalse(comparison.agrees(row("q", 0, 1e-11, 1e-13)))         # a paper's 0
        self.assertTrue(comparison.agrees(row("q", 0, 1e-11, 1e-13), absolute=1e-6))
        self.assertIsNone(comparison.agrees(row("q", None, 1.0, 0.1)))
        self.assertIsNone(comparison.agrees(row("q", "about 0.2", 0.3, None)))
        self.assertIsNone(comparison.agrees(row("q", 2, math.nan, None)))

    def test_verdicts_give_differing_rows_their_cause_and_list_the_uncaused(self):
        verdicts = comparison.Verdicts({"sigmas": 2, "relative": 0.05}, [
            {"match": "theta_.*", "kind": "paper ambiguity", "cause": "the fit range"},
            {"match": "hottest_slab_z", "relative": 0.7, "cause": "wide"},
        ])
        rows = [("theta_P_n1", 1.5, 1.3, 0.01), ("hottest_slab_z", "7-10", 0.5, 0.5),
                ("other", 1.0, 2.0, 0.1), ("fig2_peak", None, 0.25, None)]
        comparison.write(rows, self.path, verdicts=verdicts)
        lines = self.path.read_text().splitlines()
        self.assertEqual(lines[0], "quantity,paper,measured,error,status,cause")
        self.assertEqual(lines[1], "theta_P_n1,1.5,1.3,0.01,differs,paper ambiguity: the fit range")
        self.assertEqual(lines[2], "hottest_slab_z,7-10,0.5,0.5,agrees,")  # its own band: 7 - 0.7 x 10
        self.assertEqual(lines[3], "other,1,2,0.1,differs,")
        self.assertEqual(lines[4], "fig2_peak,,0.25,,,")
        self.assertEqual([r.quantity for r in comparison.uncaused(rows, verdicts)], ["other"])
        self.assertEqual(comparison.read(self.path)[1].paper, "7-10")

    def test_a_verdict_without_a_cause_or_with_an_unknown_kind_is_refused(self):
        with self.assertRaises(ValueError):
            comparison.Verdicts(None, [{"match": "q"}])
        with self.assertRaises(ValueError):
            comparison.Verdicts(None, [{"match": "q", "cause": "x", "kind": "bad luck"}])


if __name__ == "__main__":
    unittest.main()
