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


if __name__ == "__main__":
    unittest.main()
